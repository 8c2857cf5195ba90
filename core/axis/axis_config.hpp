#pragma once
#include <cstdint>

#include "axis/sensor_registry.hpp"
#include "sensors/magnetometer.hpp"
#include "sensors/pot_calibration.hpp"
#include "sensors/pot_filter.hpp"
#include "settings/settings.hpp"
#include "util/axis_id.hpp"

namespace rotord {

enum class DriveType : std::uint8_t { kRelay, kRelayTwoSpeed, kRelayVoltageSelect, kHBridge };

/// Everything one axis needs, derived from the settings table whenever it
/// changes. Plain data: the axis never looks settings up by key in the tick.
struct AxisConfig {
  float min_deg = 0.0f;
  float max_deg = 360.0f;
  bool continuous = false;
  float offset_deg = 0.0f;
  float tolerance_deg = 1.0f;
  float slow_zone_deg = 10.0f;

  DriveType drive = DriveType::kRelay;
  bool has_brake = false;
  int brake_release_ms = 0;
  int brake_engage_ms = 0;
  int dir_settle_ms = 0;
  int soft_ms = 0;
  int reverse_dead_ms = 1000;
  int min_dwell_ms = 300;
  float pwm_slow_duty = 0.45f;
  float pwm_fast_duty = 1.0f;

  SensorType sensor = SensorType::kPot;  ///< its row: axis/sensor_registry.hpp
  PotCalibration pot_cal;
  PotFilterConfig pot_filter;
  float ma3_zero_deg = 0.0f;
  bool ma3_reverse = false;
  int ma3_bits = 12;
  MagChip mag_chip = MagChip::kQmc5883l;
  MagCalibration mag_cal;
  int mag_lowpass_ms = 0;

  float stall_deg = 2.0f;
  int stall_ms = 3000;
  float jump_deg = 15.0f;
  int move_timeout_ms = 180000;   ///< the shortest move timeout, whatever the distance
  float speed_deg_s = 6.0f;       ///< rated speed at full power
  float slow_speed_ratio = 0.3f;  ///< two-speed / voltage-select slow speed, fraction of full
  float pwm_dead_band = 0.3f;     ///< H-bridge duty below which the motor does not turn
  float coast_s = 0.15f;
  bool coast_learn = true;
  float slip_deg = 2.0f;  ///< uncommanded motion at rest counted as a slip (0 = off)
  bool slip_fault = false;
  bool slip_rehold = false;  ///< a brakeless axis turns back after a slip (slip.rehold)
};

AxisConfig axis_config_from(const settings::Settings& s, AxisId axis);

}  // namespace rotord
