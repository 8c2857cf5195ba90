#pragma once
#include <cstdint>

namespace rotord::sim {

/// How the controller's outputs power the motor. The numbers are the values of
/// the controller's `az.drive` / `el.drive` setting, so a profile can pass
/// them on unchanged.
enum class DriveKind : std::uint8_t {
  kRelay = 0,               ///< CW/CCW relays, one speed
  kRelayTwoSpeed = 1,       ///< relays plus a fast/slow output (kSpeedFast)
  kRelayVoltageSelect = 2,  ///< relays plus a creep/fast supply relay (kVoltageFast)
  kHBridge = 3,             ///< H-bridge PWM duty (kPwmCw / kPwmCcw)
};

/// One axis of the plant model (plant.hpp). Angles are output
/// degrees (the motor-side angle is scaled to the output too).
struct AxisPlantParams {
  double v_max_deg_s = 6.0;       ///< full speed at load factor 1
  double tau_m_s = 0.2;           ///< powered speed time constant
  double tau_c_s = 0.15;          ///< unpowered coast time constant
  double backlash_deg = 1.0;      ///< total gear play between motor and output
  double relay_delay_s = 0.010;   ///< operate (and release) time of the drive relays
  double pwm_dead_band = 0.0;     ///< H-bridge duty below which the motor does not turn (d0)
  double slow_speed_ratio = 0.5;  ///< two-speed slow / voltage-select creep, fraction of v_max
  double stop_min_deg = -3.0;     ///< hard mechanical end stops
  double stop_max_deg = 363.0;
  bool continuous = false;  ///< no end stops at all (slip ring)
  DriveKind drive = DriveKind::kRelay;
  bool has_brake = false;            ///< brake holds unless kBrake is energised
  double brake_decel_deg_s2 = 60.0;  ///< deceleration while the brake drags a moving axis
};

}  // namespace rotord::sim
