#pragma once
#include <cstdint>
#include <optional>

#include "hal/i2c.hpp"

namespace rotord {

enum class MagChip : std::uint8_t { kQmc5883l, kHmc5883l };

/// One raw field sample in the chip's counts.
struct MagSample {
  std::int16_t x = 0, y = 0, z = 0;
};

/// Register-level driver of a QMC5883L (address 0x0D) or HMC5883L (0x1E):
/// continuous measurement, read the X/Y/Z registers. No heap, one short I2C
/// transaction per call.
class Magnetometer {
 public:
  static constexpr std::uint8_t kQmcAddress = 0x0D;
  static constexpr std::uint8_t kHmcAddress = 0x1E;

  enum class Status : std::uint8_t { kOk, kNoAnswer, kWrongChip, kOverflow };

  explicit Magnetometer(hal::I2c& bus) : bus_(bus) {}
  void set_chip(MagChip chip);
  MagChip chip() const { return chip_; }

  /// Checks the chip's identity and starts continuous measurement.
  Status begin();
  bool started() const { return started_; }
  /// The latest sample; begin() again after kNoAnswer (the next read does).
  Status read(MagSample& out);

 private:
  hal::I2c& bus_;
  MagChip chip_ = MagChip::kQmc5883l;
  bool started_ = false;
};

/// Hard-iron calibration from the extremes seen while turning the sensor a
/// full circle: the offset is the middle of each axis's range, and each axis
/// is scaled by its half-range (a first-order soft-iron correction, which
/// makes an elliptical trace circular).
struct MagCalibration {
  float x_min = -1000.0f, x_max = 1000.0f;
  float y_min = -1000.0f, y_max = 1000.0f;
  float declination_deg = 0.0f;  ///< east positive: true = magnetic + declination
  bool reverse = false;          ///< the heading falls when the rotator turns clockwise
  bool valid() const { return x_max > x_min && y_max > y_min; }
  bool operator==(const MagCalibration&) const = default;
};

/// Heading in degrees [0, 360) from a calibrated sample, or nullopt when the
/// corrected field is too weak to point anywhere (under 1/4 of the
/// calibrated radius: a magnet nearby, a wrong calibration, a dead axis).
std::optional<float> mag_heading_deg(const MagSample& sample, const MagCalibration& cal);

/// Smooths a heading without the 359/0 trap: each new value is unwrapped
/// next to the previous output before the low-pass, and the output is
/// wrapped back into [0, 360). Averaging 359 and 1 gives 0, not 180, and a
/// rotator turning through north many times never accumulates an error.
class HeadingFilter {
 public:
  /// `alpha` in (0, 1]: the weight of a new value (1 = no smoothing).
  explicit HeadingFilter(float alpha = 1.0f) : alpha_(alpha) {}
  void set_alpha(float alpha) { alpha_ = alpha; }
  void reset() { have_ = false; }
  float step(float heading_deg);

 private:
  float alpha_;
  bool have_ = false;
  float out_deg_ = 0.0f;
};

}  // namespace rotord
