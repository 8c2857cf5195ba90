#pragma once
#include <cstddef>
#include <string_view>

#include "sim/adc_scale.hpp"
#include "sim/profiles.hpp"

namespace rotord::sim {

/// The settings that say which sensor an axis reads and how it is
/// calibrated. The profiles derive them from their axes, and the HIL plant
/// rebuilds them for the sensor its options fit: one rule for both, so the
/// emulated firmware is calibrated exactly as `rotord --sim` is.
struct SensorKeys {
  const char* sensor;
  const char* pot_cal_lo_counts;
  const char* pot_cal_lo_deg;
  const char* pot_cal_hi_counts;
  const char* pot_cal_hi_deg;
  const char* ma3_zero_deg;
};

inline constexpr SensorKeys kAzSensorKeys{"az.sensor",         "az.pot_cal_lo_counts",
                                          "az.pot_cal_lo_deg", "az.pot_cal_hi_counts",
                                          "az.pot_cal_hi_deg", "az.ma3_zero_deg"};
inline constexpr SensorKeys kElSensorKeys{"el.sensor",         "el.pot_cal_lo_counts",
                                          "el.pot_cal_lo_deg", "el.pot_cal_hi_counts",
                                          "el.pot_cal_hi_deg", "el.ma3_zero_deg"};

/// Whether `key` is one of an axis's sensor settings.
constexpr bool is_sensor_key(std::string_view key, const SensorKeys& k) {
  return key == k.sensor || key == k.pot_cal_lo_counts || key == k.pot_cal_lo_deg ||
         key == k.pot_cal_hi_counts || key == k.pot_cal_hi_deg || key == k.ma3_zero_deg;
}

/// Appends the sensor settings of axis `a` at out[n], advancing n: its
/// sensor type, then the pot's two-point calibration at the range ends or
/// the MA3's zero. The caller's array has room (a constant list that
/// overflows does not compile).
constexpr void add_sensor_overrides(const AxisProfile& a, const SensorKeys& k, SettingOverride* out,
                                    std::size_t& n) {
  out[n++] = {k.sensor, static_cast<double>(a.sensor)};
  if (a.sensor == SensorType::kPot) {
    // The unrounded codes, so a noise-free pot reads the true angle to
    // within half a count.
    out[n++] = {k.pot_cal_lo_counts, adc_counts_exact(a.pot.v_at_min_v)};
    out[n++] = {k.pot_cal_lo_deg, a.min_deg};
    out[n++] = {k.pot_cal_hi_counts, adc_counts_exact(a.pot.v_at_max_v)};
    out[n++] = {k.pot_cal_hi_deg, a.max_deg};
  } else {
    out[n++] = {k.ma3_zero_deg, 0.0};  // the simulated encoder reads 0 at theta = 0
  }
}

}  // namespace rotord::sim
