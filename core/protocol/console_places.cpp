// The console's commands for where the beam points (issue 26): the bearing
// to a place, turning there, and the presets. The same parser and checks as
// the REST API's (rotator/place.hpp, settings/preset.hpp).
#include <cstdio>

#include "command/typed.hpp"
#include "protocol/console_reply.hpp"
#include "protocol/console_session.hpp"
#include "rotator/place.hpp"
#include "settings/preset.hpp"

namespace rotord::protocol {
namespace {

using console::send;

const char* path_name(const PlaceQuery& q) {
  return q.path == tracking::Path::kLong ? "long" : "short";
}

/// The command's error for a refused move.
const char* move_error(Error e) {
  return e == Error::kFaulted ? "an axis has a latched fault: reset clears it" : error_name(e);
}

}  // namespace

void ConsoleSession::bearing(std::string_view args, ByteSink& out) {
  PlaceQuery q;
  if (const char* why = parse_place(args, q)) return send(out, "error: %s", why);
  const PlaceAim aim = aim_at(controller_, q);
  if (!aim.reachable)
    send(out, "bearing %.1f deg, %.0f km, %s path: out of reach (%s)", aim.bearing.azimuth_deg,
         aim.bearing.distance_km, path_name(q), aim.why);
  send(out, "ok bearing %.1f deg, %.0f km, %s path", aim.bearing.azimuth_deg,
       aim.bearing.distance_km, path_name(q));
}

void ConsoleSession::turn(std::string_view args, ByteSink& out) {
  PlaceQuery q;
  if (const char* why = parse_place(args, q)) return send(out, "error: %s", why);
  PlaceAim aim;
  const Error e = command::turn_to_place(controller_, origin(), q, aim);
  if (!aim.reachable) return send(out, "error: %s", aim.why);
  if (e != Error::kOk) return send(out, "error: %s", move_error(e));
  send(out, "ok turning to %.1f deg (%.0f km, %s path)", aim.bearing.azimuth_deg,
       aim.bearing.distance_km, path_name(q));
}

void ConsoleSession::presets(std::string_view, ByteSink& out) {
  int count = 0;
  for (std::size_t n = 0; n < settings::kPresetCount; ++n) {
    settings::Preset p;
    if (settings::parse_preset(controller_.settings().text(settings::preset_id(n)), p) != nullptr)
      continue;
    send(out, "preset.%u %.1f%s %s", static_cast<unsigned>(n + 1), p.az_deg,
         p.long_path ? " LP" : "", p.name);
    ++count;
  }
  send(out, "ok %d of %u presets", count, static_cast<unsigned>(settings::kPresetCount));
}

void ConsoleSession::preset(std::string_view args, ByteSink& out) {
  settings::Preset p;
  if (args.empty()) return send(out, "error: give the preset's name (presets lists them)");
  const Error e = command::turn_to_preset(controller_, origin(), args, p);
  if (e == Error::kNotFound) return send(out, "error: no preset of that name (presets lists them)");
  if (e != Error::kOk) return send(out, "error: %s: heading %.1f", move_error(e), p.az_deg);
  send(out, "ok turning to %s, %.1f deg", p.name, p.az_deg);
}

}  // namespace rotord::protocol
