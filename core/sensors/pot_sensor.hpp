#pragma once
#include "hal/analog_in.hpp"
#include "sensors/position_sensor.hpp"

namespace rotord {

/// Two-point linear calibration: counts_lo read at deg_lo, counts_hi at deg_hi.
struct PotCalibration {
  float counts_lo = 0.0f;
  float deg_lo = 0.0f;
  float counts_hi = 4095.0f;
  float deg_hi = 360.0f;

  float to_deg(float counts) const {
    return deg_lo + (counts - counts_lo) * (deg_hi - deg_lo) / (counts_hi - counts_lo);
  }
};

/// Potentiometer wiper on an ADC. Each read takes kSamples conversions and
/// averages the middle half (a trimmed mean: rejects single spikes like a
/// median, averages white noise like a mean).
class PotSensor final : public PositionSensor {
 public:
  static constexpr int kSamples = 8;
  /// Codes this close to either rail mean an open or shorted pot.
  static constexpr int kRailMarginCounts = 8;

  explicit PotSensor(hal::AnalogIn& adc) : adc_(adc) {}
  void set_calibration(const PotCalibration& cal) { cal_ = cal; }
  PositionReading read() override;
  bool single_turn() const override { return false; }

 private:
  hal::AnalogIn& adc_;
  PotCalibration cal_;
};

}  // namespace rotord
