#pragma once
#include "hal/i2c.hpp"
#include "sensors/magnetometer.hpp"
#include "sensors/position_sensor.hpp"

namespace rotord {

/// Azimuth from a magnetometer on the mast (az.sensor = mag): heading with
/// hard-iron calibration and declination, smoothed across north without the
/// 359/0 trap. Single-turn: the axis unwraps it into its travel.
class MagSensor final : public PositionSensor {
 public:
  explicit MagSensor(hal::I2c& bus) : mag_(bus) {}
  void configure(MagChip chip, const MagCalibration& cal, int lowpass_ms);
  PositionReading read(Millis now) override;
  bool single_turn() const override { return true; }
  void restart() override { filter_.reset(); }
  /// The last raw sample, for the calibration procedure (min/max per axis).
  const MagSample& last_sample() const { return sample_; }

 private:
  Magnetometer mag_;
  MagChip chip_ = MagChip::kQmc5883l;
  MagCalibration cal_;
  int lowpass_ms_ = 0;
  HeadingFilter filter_;
  MagSample sample_;
  Millis last_ = 0;
};

}  // namespace rotord
