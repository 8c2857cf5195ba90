#include "sensors/ma3_sensor.hpp"

#include "motion/angles.hpp"

namespace rotord {

std::optional<int> ma3_decode_code(const hal::PwmPeriod& period, int bits) {
  if (!period.valid) return std::nullopt;
  const std::uint64_t total = std::uint64_t{period.high_us} + period.low_us;
  if (total == 0) return std::nullopt;
  const std::int64_t counts = std::int64_t{1} << bits;
  // Rounded integer arithmetic: the same result on the Pico as on the host.
  std::int64_t code = (static_cast<std::int64_t>(period.high_us) * (counts + 2) +
                       static_cast<std::int64_t>(total / 2)) /
                          static_cast<std::int64_t>(total) -
                      1;
  if (code < 0) code = 0;
  if (code > counts - 1) code = counts - 1;
  return static_cast<int>(code);
}

PositionReading Ma3Sensor::read(Millis /*now*/) {
  PositionReading r;
  const auto code = ma3_decode_code(input_.read(), bits_);
  if (!code) {
    r.fault = SensorFault::kNoSignal;
    return r;
  }
  r.raw = static_cast<float>(*code);
  float deg = static_cast<float>(*code) * 360.0f / static_cast<float>(1 << bits_);
  if (reverse_) deg = -deg;
  r.deg = wrap_360(deg - zero_deg_);
  r.ok = true;
  return r;
}

}  // namespace rotord
