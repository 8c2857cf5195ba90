// Presets over REST (docs/web_api.md, "Presets"): named headings stored in
// the settings rows preset.1..16 (settings/preset.hpp), saved like any
// setting, so they survive a restart and travel with an export.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "json/json_reader.hpp"
#include "rotator/place.hpp"
#include "settings/preset.hpp"
#include "web/place_api.hpp"

namespace rotord::web {
namespace {

using settings::Preset;

struct PresetBody {
  char name[settings::kPresetNameMaxBytes + 1] = {};
  bool has_name = false;
  bool has_az = false;
  double az_deg = 0;
  bool long_path = false;
};

/// Reads {"name", "az", "long_path"}; nullptr, or why not.
const char* read_body(std::string_view body, PresetBody& b, bool name_only) {
  JsonObjectReader reader(body);
  if (!reader.valid()) return "invalid JSON";
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    if (key == "name" && value.type == JsonType::kString) {
      if (value.truncated) return "a preset name is at most 20 bytes";
      if (const char* why = settings::check_preset_name(value.text)) return why;
      std::memcpy(b.name, value.text.data(), value.text.size());
      b.name[value.text.size()] = '\0';
      b.has_name = true;
    } else if (!name_only && key == "az" && value.type == JsonType::kNumber) {
      b.az_deg = value.number;
      b.has_az = true;
    } else if (!name_only && key == "long_path" && value.type == JsonType::kBool) {
      b.long_path = value.boolean;
    } else {
      return name_only ? "the body is {\"name\": ...}"
                       : "the body is {\"name\": ..., \"az\": degrees, \"long_path\": bool}";
    }
  }
  if (!reader.valid()) return "invalid JSON";
  if (!b.has_name) return "give the preset's name";
  if (!name_only && !b.has_az) return "give az (degrees, 0..360)";
  if (!name_only && (!std::isfinite(b.az_deg) || b.az_deg < 0.0 || b.az_deg > 360.0))
    return "az is outside 0..360";
  return nullptr;
}

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

/// Writes `text` into slot `n` and saves; false (after answering) on failure.
bool store(Api& api, std::size_t n, std::string_view text, const Api::Call& call) {
  settings::Settings& s = api.controller().settings();
  char old[32];
  const std::string_view before = s.text(settings::preset_id(n));
  if (!before.empty()) std::memcpy(old, before.data(), before.size());
  const std::size_t old_len = before.size();
  const settings::Rejection r = s.set_text(settings::preset_id(n), text);
  if (r.error != Error::kOk) {
    send_error(call.out, 422, r.reason, call.options);
    return false;
  }
  if (!api.persist_settings()) {
    s.set_text(settings::preset_id(n), std::string_view(old, old_len));
    send_error(call.out, 500, "the presets could not be saved; nothing was changed", call.options);
    return false;
  }
  return true;
}

}  // namespace

Api::Outcome get_presets(Api& api, const Api::Call& call) {
  send_json(call.out, 200, call.options,
            [&](JsonWriter& w) { write_presets(w, api.controller().settings()); });
  return Api::Outcome::kDone;
}

Api::Outcome post_presets(Api& api, const Api::Call& call) {
  PresetBody b;
  if (const char* why = read_body(call.request.body, b, false)) {
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
  if (const char* why = read_body(call.request.body, b, true)) {
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

Api::Outcome post_preset(Api& api, const Api::Call& call) {
  PresetBody b;
  if (const char* why = read_body(call.request.body, b, true)) {
    send_error(call.out, 400, why, call.options);
    return Api::Outcome::kDone;
  }
  Preset p;
  if (!settings::find_preset(api.controller().settings(), b.name, &p)) {
    send_error(call.out, 404, "no preset of that name", call.options);
    return Api::Outcome::kDone;
  }
  const Error e = turn_beam_to(api.controller(), p.az_deg);
  if (e != Error::kOk) {
    char why[96];
    const Limits l = api.controller().limits();
    std::snprintf(why, sizeof why, "%s: heading %.1f, travel %g..%g", error_name(e), p.az_deg,
                  static_cast<double>(l.az_min_deg), static_cast<double>(l.az_max_deg));
    send_error(call.out, e == Error::kFaulted ? 409 : 422, why, call.options);
    return Api::Outcome::kDone;
  }
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object().member("ok", true).member("name", p.name).member("az_deg", p.az_deg);
    w.end_object();
  });
  return Api::Outcome::kDone;
}

}  // namespace rotord::web
