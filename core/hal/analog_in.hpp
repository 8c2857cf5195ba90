#pragma once
#include <cstdint>

namespace rotord::hal {

/// An ADC channel (potentiometer wiper). Counts are raw converter codes.
class AnalogIn {
 public:
  virtual ~AnalogIn() = default;
  virtual std::uint16_t read_counts() = 0;
  /// Highest code the converter produces (4095 for the RP2040's 12-bit ADC).
  virtual std::uint16_t full_scale_counts() const = 0;
  /// Reference voltage, for showing volts in the calibration page.
  virtual float reference_v() const = 0;
};

}  // namespace rotord::hal
