#include "sim/actuation.hpp"

#include <algorithm>
#include <cmath>

namespace rotord::sim {

double pwm_speed_ratio(double duty, double dead_band) {
  const double d = std::clamp(duty, -1.0, 1.0);
  if (dead_band >= 1.0) return 0.0;
  const double magnitude = std::max(0.0, (std::fabs(d) - dead_band) / (1.0 - dead_band));
  return d < 0.0 ? -magnitude : magnitude;
}

namespace {

// Relay drives: both direction relays on is treated as no drive (the windings
// oppose each other), which is also what a miswired controller would get.
int relay_direction(const DriveOutputs& outputs) {
  const bool cw = outputs.on(OutputChannel::kRelayCw);
  const bool ccw = outputs.on(OutputChannel::kRelayCcw);
  return (cw ? 1 : 0) - (ccw ? 1 : 0);
}

}  // namespace

Actuation actuation_from(const AxisPlantParams& params, const DriveOutputs& outputs) {
  Actuation a;
  a.brake_released = !params.has_brake || outputs.on(OutputChannel::kBrake);
  switch (params.drive) {
    case DriveKind::kRelay:
    case DriveKind::kRelayTwoSpeed:
    case DriveKind::kRelayVoltageSelect: {
      const int u = relay_direction(outputs);
      double speed = 1.0;
      if (params.drive == DriveKind::kRelayTwoSpeed && !outputs.on(OutputChannel::kSpeedFast)) {
        speed = params.slow_speed_ratio;
      }
      if (params.drive == DriveKind::kRelayVoltageSelect &&
          !outputs.on(OutputChannel::kVoltageFast)) {
        speed = params.slow_speed_ratio;
      }
      a.powered = u != 0;
      a.target_ratio = u * speed;
      break;
    }
    case DriveKind::kHBridge: {
      const double duty = static_cast<double>(outputs.get(OutputChannel::kPwmCw)) -
                          static_cast<double>(outputs.get(OutputChannel::kPwmCcw));
      // Below the dead band current still flows (the motor hums and holds at
      // zero speed target), so it counts as powered.
      a.powered = duty != 0.0;
      a.target_ratio = pwm_speed_ratio(duty, params.pwm_dead_band);
      break;
    }
  }
  return a;
}

}  // namespace rotord::sim
