#include "command/typed.hpp"

#include "net/line_access.hpp"

namespace rotord::command {

bool may_control(const Controller& controller, const access::Peer& peer) {
  return access::may_control(controller.settings(), peer) && !controller.control_lock().held();
}

void stop(Controller& controller) {
  controller.stop();
}

Error stop_axis(Controller& controller, AxisId axis) {
  if (axis == AxisId::kEl && !controller.has_el()) return Error::kNotSupported;
  controller.move(axis, Direction::kNone);  // a faulted axis is stopped anyway
  return Error::kOk;
}

Error go_to(Controller& controller, std::optional<float> az_deg, std::optional<float> el_deg,
            AzTarget mode, CommandSource source) {
  return controller.go_to(az_deg, el_deg, mode, source);
}

Error move(Controller& controller, AxisId axis, Direction dir, int speed_pct) {
  return controller.move(axis, dir, speed_pct);
}

void end_jog(Controller& controller, AxisId axis) {
  controller.end_jog(axis);
}

Error park(Controller& controller) {
  return controller.park();
}

Error reset(Controller& controller) {
  return controller.reset();
}

Error set_speed(Controller& controller, int speed_pct) {
  return controller.set_speed_pct(speed_pct);
}

Error turn_to_place(Controller& controller, const PlaceQuery& place, PlaceAim& aim) {
  aim = aim_at(controller, place);
  if (!aim.reachable) return Error::kOutOfRange;
  return turn_to(controller, aim);
}

Error turn_to_preset(Controller& controller, std::string_view name, settings::Preset& preset) {
  if (!settings::find_preset(controller.settings(), name, &preset)) return Error::kNotFound;
  return turn_beam_to(controller, preset.az_deg);
}

}  // namespace rotord::command
