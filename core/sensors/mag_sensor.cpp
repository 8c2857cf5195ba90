#include "sensors/mag_sensor.hpp"

namespace rotord {

void MagSensor::configure(MagChip chip, const MagCalibration& cal, int lowpass_ms) {
  // A new calibration moves the heading in one step. Smoothing across it
  // would show a turn that never happened, slewing for several time
  // constants, so the filter starts again from the next sample.
  if (!(cal == cal_) || chip != chip_) filter_.reset();
  chip_ = chip;
  mag_.set_chip(chip);
  cal_ = cal;
  lowpass_ms_ = lowpass_ms;
}

PositionReading MagSensor::read(Millis now) {
  PositionReading r;
  const Magnetometer::Status status = mag_.read(sample_);
  if (status == Magnetometer::Status::kNoAnswer || status == Magnetometer::Status::kWrongChip) {
    filter_.reset();
    r.fault = SensorFault::kNoSignal;
    return r;
  }
  const auto heading = mag_heading_deg(sample_, cal_);
  if (status == Magnetometer::Status::kOverflow || !heading) {
    r.fault = SensorFault::kImplausible;
    return r;
  }
  r.raw = *heading;
  float alpha = 1.0f;
  if (lowpass_ms_ > 0) {
    const float dt = now > last_ ? static_cast<float>(now - last_) : 0.0f;
    alpha = dt / (static_cast<float>(lowpass_ms_) + dt);
  }
  last_ = now;
  filter_.set_alpha(alpha);
  r.deg = filter_.step(*heading);
  r.ok = true;
  return r;
}

}  // namespace rotord
