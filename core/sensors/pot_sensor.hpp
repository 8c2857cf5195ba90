#pragma once
#include "hal/analog_in.hpp"
#include "sensors/position_sensor.hpp"
#include "sensors/pot_calibration.hpp"
#include "sensors/pot_filter.hpp"

namespace rotord {

/// Potentiometer wiper on an ADC. Each reading oversamples (a burst of
/// conversions, spikes dropped, the rest averaged), then the readings pass
/// a median-of-three and an optional low-pass, and the calibration table
/// turns counts into degrees.
class PotSensor final : public PositionSensor {
 public:
  /// Codes this close to either rail mean an open or shorted pot.
  static constexpr int kRailMarginCounts = 8;

  explicit PotSensor(hal::AnalogIn& adc) : adc_(adc) {}
  void configure(const PotCalibration& cal, const PotFilterConfig& filter);
  void set_calibration(const PotCalibration& cal) { cal_ = cal; }
  PositionReading read(Millis now) override;
  bool single_turn() const override { return false; }
  void restart() override { filter_.reset(); }

 private:
  hal::AnalogIn& adc_;
  PotCalibration cal_;
  PotFilterConfig filter_config_;
  PotFilter filter_;
};

}  // namespace rotord
