#include "axis/sensor_registry.hpp"

#include <array>
#include <cmath>

#include "axis/axis_config.hpp"
#include "axis/axis_status.hpp"

namespace rotord {
namespace {

// ---- pot: a wiper on an ADC, multi-turn, a calibration table ----

PositionSensor* pot_fit(SensorSlots& s, const AxisIo& io) {
  return io.pot ? &s.pot.emplace(*io.pot) : nullptr;
}
void pot_configure(SensorSlots& s, const AxisConfig& c) {
  if (s.pot) s.pot->configure(c.pot_cal, c.pot_filter);
}
bool pot_frame_changed(const AxisConfig& a, const AxisConfig& b) {
  if (a.pot_cal.count != b.pot_cal.count) return true;
  for (std::size_t n = 0; n < static_cast<std::size_t>(b.pot_cal.count); ++n)
    if (a.pot_cal.points[n].counts != b.pot_cal.points[n].counts ||
        a.pot_cal.points[n].deg != b.pot_cal.points[n].deg)
      return true;
  return false;
}
float pot_resolution_deg(const AxisConfig& c) {
  const auto& lo = c.pot_cal.points[0];
  const auto& hi = c.pot_cal.points[static_cast<std::size_t>(c.pot_cal.count - 1)];
  const float counts = std::fabs(hi.counts - lo.counts);
  return counts > 0.0f ? std::fabs(hi.deg - lo.deg) / counts : 0.1f;
}
void pot_publish(const SensorSlots&, const AxisIo& io, const AxisConfig&, bool, AxisStatus& st) {
  st.raw_full_scale = static_cast<float>(io.pot->full_scale_counts());
  st.adc_ref_v = io.pot->reference_v();
}

// ---- ma3: an absolute encoder's PWM, single-turn ----

PositionSensor* ma3_fit(SensorSlots& s, const AxisIo& io) {
  return io.ma3 ? &s.ma3.emplace(*io.ma3) : nullptr;
}
void ma3_configure(SensorSlots& s, const AxisConfig& c) {
  if (s.ma3) s.ma3->configure(c.ma3_bits, c.ma3_zero_deg, c.ma3_reverse);
}
bool ma3_frame_changed(const AxisConfig& a, const AxisConfig& b) {
  return a.ma3_zero_deg != b.ma3_zero_deg || a.ma3_reverse != b.ma3_reverse ||
         a.ma3_bits != b.ma3_bits;
}
float ma3_resolution_deg(const AxisConfig& c) {
  return 360.0f / static_cast<float>(ma3_timing(c.ma3_bits).counts);
}
void ma3_publish(const SensorSlots&, const AxisIo&, const AxisConfig& c, bool, AxisStatus& st) {
  st.raw_full_scale = static_cast<float>(ma3_timing(c.ma3_bits).counts);
}

// ---- mag: a magnetometer's heading on the azimuth's I2C bus ----

PositionSensor* mag_fit(SensorSlots& s, const AxisIo& io) {
  return io.i2c ? &s.mag.emplace(*io.i2c) : nullptr;
}
void mag_configure(SensorSlots& s, const AxisConfig& c) {
  if (s.mag) s.mag->configure(c.mag_chip, c.mag_cal, c.mag_lowpass_ms);
}
bool mag_frame_changed(const AxisConfig& a, const AxisConfig& b) {
  return !(a.mag_cal == b.mag_cal) || a.mag_chip != b.mag_chip;
}
float mag_resolution_deg(const AxisConfig&) {
  return 0.1f;  // a heading from 12-16 bit field counts
}
void mag_publish(const SensorSlots& s, const AxisIo&, const AxisConfig&, bool answered,
                 AxisStatus& st) {
  // A weak or distorted field still gives raw samples, which is what the
  // magnetometer calibration needs; only a silent chip gives none.
  const MagSample& m = s.mag->last_sample();
  st.mag_valid = answered;
  st.mag_x = m.x;
  st.mag_y = m.y;
  st.mag_z = m.z;
}

using T = SensorType;
using In = SensorInput;

// One row per type, in the order of SensorType.
constexpr std::array<SensorInfo, kSensorTypeCount> kSensorTypes = {{
    {T::kPot, "pot", "pot", "counts", In::kAnalog, false, pot_fit, pot_configure, pot_frame_changed,
     pot_resolution_deg, pot_publish},
    {T::kMa3, "ma3", "MA3", "code", In::kPwm, false, ma3_fit, ma3_configure, ma3_frame_changed,
     ma3_resolution_deg, ma3_publish},
    {T::kMag, "mag", "magnetometer", "deg", In::kI2c, true, mag_fit, mag_configure,
     mag_frame_changed, mag_resolution_deg, mag_publish},
}};

constexpr bool rows_in_order() {
  for (std::size_t n = 0; n < kSensorTypes.size(); ++n)
    if (static_cast<std::size_t>(kSensorTypes[n].type) != n) return false;
  return true;
}
static_assert(rows_in_order(), "one row a SensorType, in its order");

}  // namespace

std::span<const SensorInfo> sensor_types() {
  return kSensorTypes;
}

const SensorInfo& sensor_info(SensorType type) {
  return kSensorTypes[static_cast<std::size_t>(type)];
}

const SensorInfo* find_sensor(int stored) {
  if (stored < 0 || static_cast<std::size_t>(stored) >= kSensorTypes.size()) return nullptr;
  return &kSensorTypes[static_cast<std::size_t>(stored)];
}

}  // namespace rotord
