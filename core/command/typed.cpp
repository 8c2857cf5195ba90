#include "command/typed.hpp"

#include <cstdio>

#include "net/line_access.hpp"

namespace rotord::command {
namespace {

float deg(std::optional<float> v) {
  return v.value_or(NAN);
}

/// A move's words for the log: "az cw", "el down", "az stop".
std::string_view move_words(AxisId axis, Direction dir) {
  static constexpr std::string_view kWords[2][3] = {{"az stop", "az cw", "az ccw"},
                                                    {"el stop", "el up", "el down"}};
  return kWords[axis == AxisId::kEl][dir == Direction::kCw ? 1 : dir == Direction::kCcw ? 2 : 0];
}

}  // namespace

bool in_control(const Controller& controller, const access::Peer& peer) {
  return access::may_control(controller.settings(), peer) && !controller.control_lock().held();
}

bool may_control(Controller& controller, const Origin& from, std::string_view what) {
  if (in_control(controller, from.peer)) return true;
  told(controller, from, what, controller.control_lock().held() ? "LOCKED" : "DENIED");
  return false;
}

void stop(Controller& controller, const Origin& from) {
  controller.stop();
  told(controller, from, "stop", Error::kOk);
}

Error stop_axis(Controller& controller, const Origin& from, AxisId axis) {
  Error e = Error::kNotSupported;
  if (axis != AxisId::kEl || controller.has_el()) {
    controller.move(axis, Direction::kNone);  // a faulted axis is stopped anyway
    e = Error::kOk;
  }
  return told(controller, from, "stop", e, NAN, NAN, axis == AxisId::kEl ? "el" : "az");
}

Error go_to(Controller& controller, const Origin& from, std::optional<float> az_deg,
            std::optional<float> el_deg, AzTarget mode, CommandSource source) {
  return told(controller, from, "goto", controller.go_to(az_deg, el_deg, mode, source), deg(az_deg),
              deg(el_deg));
}

Error move(Controller& controller, const Origin& from, AxisId axis, Direction dir, int speed_pct) {
  return told(controller, from, "move", controller.move(axis, dir, speed_pct), NAN, NAN,
              move_words(axis, dir));
}

void end_jog(Controller& controller, const Origin& from, AxisId axis) {
  controller.end_jog(axis);
  told(controller, from, "move", Error::kOk, NAN, NAN, move_words(axis, Direction::kNone));
}

Error park(Controller& controller, const Origin& from) {
  return told(controller, from, "park", controller.park());
}

Error reset(Controller& controller, const Origin& from) {
  return told(controller, from, "reset", controller.reset());
}

Error set_speed(Controller& controller, const Origin& from, int speed_pct) {
  char pct[16];
  std::snprintf(pct, sizeof pct, "%d %%", speed_pct);
  return told(controller, from, "speed", controller.set_speed_pct(speed_pct), NAN, NAN, pct);
}

Error turn_to_place(Controller& controller, const Origin& from, const PlaceQuery& place,
                    PlaceAim& aim) {
  aim = aim_at(controller, place);
  const Error e = aim.reachable ? turn_to(controller, aim) : Error::kOutOfRange;
  return told(controller, from, "place", e, static_cast<float>(aim.bearing.azimuth_deg), NAN,
              place.locator);
}

Error turn_to_preset(Controller& controller, const Origin& from, std::string_view name,
                     settings::Preset& preset) {
  Error e = Error::kNotFound;
  if (settings::find_preset(controller.settings(), name, &preset))
    e = turn_beam_to(controller, preset.az_deg);
  return told(controller, from, "preset", e, e == Error::kNotFound ? NAN : float(preset.az_deg),
              NAN, name);
}

}  // namespace rotord::command
