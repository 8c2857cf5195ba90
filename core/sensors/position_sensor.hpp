#pragma once
#include <cstdint>

#include "util/time.hpp"

namespace rotord {

enum class SensorFault : std::uint8_t {
  kNone,
  kNoSignal,     ///< no PWM edges (MA3 unplugged), no I2C answer
  kOutOfRange,   ///< ADC at a rail: open or shorted wiper
  kImplausible,  ///< the reading disagrees with itself (noise burst, glitching PWM)
};

/// One decoded position sample, in the sensor's own frame (no offset).
struct PositionReading {
  bool ok = false;
  float deg = 0.0f;  ///< calibrated angle; 0..360 for single-turn sensors
  float raw = 0.0f;  ///< ADC counts or encoder duty code, for calibration pages
  SensorFault fault = SensorFault::kNone;
};

class PositionSensor {
 public:
  virtual ~PositionSensor() = default;
  /// One reading at `now` (filters that work in real time need it).
  virtual PositionReading read(Millis now) = 0;
  /// True for sensors that repeat every 360 deg (MA3, magnetometer); the axis
  /// unwraps them into the mechanical range.
  virtual bool single_turn() const = 0;
  /// Forgets filter history. The axis calls it when this sensor becomes its
  /// sensor again (a settings change), so readings kept from the last time
  /// it was read do not surface as an implausible jump.
  virtual void restart() {}
};

}  // namespace rotord
