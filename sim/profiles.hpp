#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "axis/sensor_registry.hpp"
#include "sim/plant_params.hpp"

namespace rotord::sim {

/// Wiper voltage at the two ends of the working range (linear in between).
struct PotMapping {
  double v_at_min_v = 0.05;
  double v_at_max_v = 3.0;
  double sigma_v = 0.0;  ///< conversion noise, one sample

  /// Slope and offset for an axis whose working range is [min_deg, max_deg].
  constexpr double k_v_per_deg(double min_deg, double max_deg) const {
    return (v_at_max_v - v_at_min_v) / (max_deg - min_deg);
  }
  constexpr double v0_v(double min_deg, double max_deg) const {
    return v_at_min_v - k_v_per_deg(min_deg, max_deg) * min_deg;
  }
};

/// A simulated axis: its mechanics, its working range (what the controller is
/// told) and the sensors fitted. End stops and switches sit just outside the
/// range (see make_axis in profiles.cpp).
struct AxisProfile {
  AxisPlantParams plant;
  double min_deg = 0.0;
  double max_deg = 360.0;
  /// The sensor type the profile's settings choose (its row says which of
  /// the models below it reads: sim_rotator.cpp fits models by input).
  SensorType sensor = SensorType::kPot;
  PotMapping pot;
  double ma3_sigma_deg = 0.03;
  bool has_limit_switches = true;
  double limit_cw_deg = 361.0;  ///< CW / UP switch closed at or above this
  double limit_ccw_deg = -1.0;  ///< CCW / DOWN switch closed at or below this
  bool has_t1 = false;          ///< overlap threshold: closed above 360 deg
  bool has_t2 = false;          ///< overlap threshold: closed below 0 deg
  double t1_above_deg = 360.0;
  double t2_below_deg = 0.0;
};

/// One entry for the controller's settings table; keys are the table's keys.
struct SettingOverride {
  const char* key;
  double value;
};

struct Profile {
  const char* name;
  const char* description;
  bool has_el;
  AxisProfile az;
  AxisProfile el;  ///< ignored when !has_el
  std::span<const SettingOverride> overrides;
};

/// Profile the Linux daemon starts with when none is chosen.
inline constexpr std::string_view kDefaultProfileName = "g5500";

/// nullptr when unknown.
const Profile* find_profile(std::string_view name);
/// All profiles, in a stable order (for help text and tests).
std::span<const Profile* const> all_profiles();

}  // namespace rotord::sim
