#pragma once
#include <cstdint>

namespace rotord::sim {

/// The RP2040's 12-bit ADC as the pot sees it. Shared by the pot fake and by
/// the profiles' calibration overrides, so both use the same scale.
inline constexpr double kAdcVref_v = 3.3;
inline constexpr std::uint16_t kAdcFullScaleCounts = 4095;

/// Ideal (unrounded) converter code for a voltage.
constexpr double adc_counts_exact(double volts) {
  return volts / kAdcVref_v * static_cast<double>(kAdcFullScaleCounts);
}

/// One ADC count in volts (0.806 mV), for noise figures given in LSB.
inline constexpr double kAdcLsb_v = kAdcVref_v / static_cast<double>(kAdcFullScaleCounts);

}  // namespace rotord::sim
