// Presets over REST (docs/web_api.md, "Presets"): named headings stored in
// the settings rows preset.1..16 (settings/preset.hpp), saved like any
// setting, so they survive a restart and travel with an export.
#include <cmath>
#include <cstdio>

#include "command/json_args.hpp"
#include "command/settings_commands.hpp"
#include "rotator/place.hpp"
#include "settings/preset.hpp"
#include "web/place_api.hpp"

namespace rotord::web {
namespace {

using settings::Preset;

using command::PresetBody;

void write_presets(JsonWriter& w, const settings::Settings& s) {
  w.begin_object().member("max", static_cast<int>(settings::kPresetCount));
  w.key("presets").begin_array();
  for (std::size_t n = 0; n < settings::kPresetCount; ++n) {
    Preset p;
    if (settings::parse_preset(s.text(settings::preset_id(n)), p) != nullptr) continue;
    w.begin_object()
        .member("slot", static_cast<int>(n + 1))
        .member("name", p.name)
        .member("az_deg", p.az_deg)
        .member("long_path", p.long_path)
        .end_object();
  }
  w.end_array().end_object();
}

/// Writes `text` into slot `n` through the command layer's settings write
/// (saved before the answer, its log line `command set preset.N`); false
/// (after answering) on failure.
bool store(Api& api, std::size_t n, std::string_view text, const Api::Call& call) {
  const command::Store saved = api.store();
  // A preset row is no secret and no access rule: every writer the route
  // admits (a control token too) may write it.
  const command::SetResult r =
      command::set_setting(api.controller(), {"rest", call.peer}, command::Writer::kToken,
                           settings::preset_id(n), text, &saved);
  if (r.status == command::SetResult::kNotSaved)
    send_error(call.out, 500, "the presets could not be saved; nothing was changed", call.options);
  else if (r.status != command::SetResult::kOk)
    send_error(call.out, 422, r.reason, call.options);
  return r.status == command::SetResult::kOk;
}

}  // namespace

Api::Outcome get_presets(Api& api, const Api::Call& call) {
  send_json(call.out, 200, call.options,
            [&](JsonWriter& w) { write_presets(w, api.controller().settings()); });
  return Api::Outcome::kDone;
}

Api::Outcome post_presets(Api& api, const Api::Call& call) {
  PresetBody b;
  if (const char* why = command::read_preset_body(call.request.body, b, false)) {
    send_error(call.out, 400, why, call.options);
    return Api::Outcome::kDone;
  }
  const settings::Settings& s = api.controller().settings();
  std::optional<std::size_t> slot = settings::find_preset(s, b.name);
  for (std::size_t n = 0; !slot && n < settings::kPresetCount; ++n)
    if (s.text(settings::preset_id(n)).empty()) slot = n;
  if (!slot) {
    send_error(call.out, 409, "16 presets already: delete one first (POST /api/presets/delete)",
               call.options);
    return Api::Outcome::kDone;
  }
  Preset p;
  p.az_deg = b.az_deg >= 360.0 ? 0.0 : b.az_deg;
  p.long_path = b.long_path;
  std::snprintf(p.name, sizeof p.name, "%s", b.name);
  char row[32];
  const std::size_t len = settings::format_preset(p, row, sizeof row);
  if (!store(api, *slot, std::string_view(row, len), call)) return Api::Outcome::kDone;
  send_json(call.out, 200, call.options,
            [&](JsonWriter& w) { write_presets(w, api.controller().settings()); });
  return Api::Outcome::kDone;
}

Api::Outcome delete_preset(Api& api, const Api::Call& call) {
  PresetBody b;
  if (const char* why = command::read_preset_body(call.request.body, b, true)) {
    send_error(call.out, 400, why, call.options);
    return Api::Outcome::kDone;
  }
  const std::optional<std::size_t> slot =
      settings::find_preset(api.controller().settings(), b.name);
  if (!slot) {
    send_error(call.out, 404, "no preset of that name", call.options);
    return Api::Outcome::kDone;
  }
  if (!store(api, *slot, {}, call)) return Api::Outcome::kDone;
  send_json(call.out, 200, call.options,
            [&](JsonWriter& w) { write_presets(w, api.controller().settings()); });
  return Api::Outcome::kDone;
}

}  // namespace rotord::web
