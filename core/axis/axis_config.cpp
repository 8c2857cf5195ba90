#include "axis/axis_config.hpp"

#include "settings/pot_table.hpp"

namespace rotord {

using settings::Id;

namespace {

/// The settings both axes have, by axis (the az-only ones are read below).
struct AxisKeys {
  Id min_deg, max_deg, offset_deg, tolerance_deg, slow_zone_deg, drive;
  Id dir_settle_ms, soft_ms, reverse_dead_ms, min_dwell_ms, pwm_slow_duty, pwm_fast_duty;
  Id sensor, pot_samples, pot_median, pot_lowpass_ms, ma3_zero_deg, ma3_reverse, ma3_bits;
  Id stall_deg, stall_ms, jump_deg, move_timeout_s, speed_deg_s, slow_speed_ratio, pwm_dead_band;
  Id coast_s, coast_learn;
};

constexpr AxisKeys kAzKeys{
    .min_deg = Id::kAzMinDeg,
    .max_deg = Id::kAzMaxDeg,
    .offset_deg = Id::kAzOffsetDeg,
    .tolerance_deg = Id::kAzToleranceDeg,
    .slow_zone_deg = Id::kAzSlowZoneDeg,
    .drive = Id::kAzDrive,
    .dir_settle_ms = Id::kAzDirSettleMs,
    .soft_ms = Id::kAzSoftMs,
    .reverse_dead_ms = Id::kAzReverseDeadMs,
    .min_dwell_ms = Id::kAzMinDwellMs,
    .pwm_slow_duty = Id::kAzPwmSlowDuty,
    .pwm_fast_duty = Id::kAzPwmFastDuty,
    .sensor = Id::kAzSensor,
    .pot_samples = Id::kAzPotSamples,
    .pot_median = Id::kAzPotMedian,
    .pot_lowpass_ms = Id::kAzPotLowpassMs,
    .ma3_zero_deg = Id::kAzMa3ZeroDeg,
    .ma3_reverse = Id::kAzMa3Reverse,
    .ma3_bits = Id::kAzMa3Bits,
    .stall_deg = Id::kAzStallDeg,
    .stall_ms = Id::kAzStallMs,
    .jump_deg = Id::kAzJumpDeg,
    .move_timeout_s = Id::kAzMoveTimeoutS,
    .speed_deg_s = Id::kAzSpeedDegS,
    .slow_speed_ratio = Id::kAzSlowSpeedRatio,
    .pwm_dead_band = Id::kAzPwmDeadBand,
    .coast_s = Id::kAzCoastS,
    .coast_learn = Id::kAzCoastLearn,
};
constexpr AxisKeys kElKeys{
    .min_deg = Id::kElMinDeg,
    .max_deg = Id::kElMaxDeg,
    .offset_deg = Id::kElOffsetDeg,
    .tolerance_deg = Id::kElToleranceDeg,
    .slow_zone_deg = Id::kElSlowZoneDeg,
    .drive = Id::kElDrive,
    .dir_settle_ms = Id::kElDirSettleMs,
    .soft_ms = Id::kElSoftMs,
    .reverse_dead_ms = Id::kElReverseDeadMs,
    .min_dwell_ms = Id::kElMinDwellMs,
    .pwm_slow_duty = Id::kElPwmSlowDuty,
    .pwm_fast_duty = Id::kElPwmFastDuty,
    .sensor = Id::kElSensor,
    .pot_samples = Id::kElPotSamples,
    .pot_median = Id::kElPotMedian,
    .pot_lowpass_ms = Id::kElPotLowpassMs,
    .ma3_zero_deg = Id::kElMa3ZeroDeg,
    .ma3_reverse = Id::kElMa3Reverse,
    .ma3_bits = Id::kElMa3Bits,
    .stall_deg = Id::kElStallDeg,
    .stall_ms = Id::kElStallMs,
    .jump_deg = Id::kElJumpDeg,
    .move_timeout_s = Id::kElMoveTimeoutS,
    .speed_deg_s = Id::kElSpeedDegS,
    .slow_speed_ratio = Id::kElSlowSpeedRatio,
    .pwm_dead_band = Id::kElPwmDeadBand,
    .coast_s = Id::kElCoastS,
    .coast_learn = Id::kElCoastLearn,
};

}  // namespace

AxisConfig axis_config_from(const settings::Settings& s, AxisId axis) {
  const AxisKeys& k = axis == AxisId::kAz ? kAzKeys : kElKeys;
  AxisConfig c;
  c.min_deg = s.f(k.min_deg);
  c.max_deg = s.f(k.max_deg);
  c.offset_deg = s.f(k.offset_deg);
  c.tolerance_deg = s.f(k.tolerance_deg);
  c.slow_zone_deg = s.f(k.slow_zone_deg);
  c.drive = static_cast<DriveType>(s.i(k.drive));
  c.dir_settle_ms = s.i(k.dir_settle_ms);
  c.soft_ms = s.i(k.soft_ms);
  c.reverse_dead_ms = s.i(k.reverse_dead_ms);
  c.min_dwell_ms = s.i(k.min_dwell_ms);
  c.pwm_slow_duty = s.f(k.pwm_slow_duty);
  c.pwm_fast_duty = s.f(k.pwm_fast_duty);
  c.sensor = static_cast<SensorType>(s.i(k.sensor));
  c.pot_cal = settings::pot_calibration_from(s, axis);
  c.pot_filter = {s.i(k.pot_samples), s.b(k.pot_median), s.i(k.pot_lowpass_ms)};
  c.ma3_zero_deg = s.f(k.ma3_zero_deg);
  c.ma3_reverse = s.b(k.ma3_reverse);
  c.ma3_bits = s.i(k.ma3_bits) == 0 ? 10 : 12;
  c.stall_deg = s.f(k.stall_deg);
  c.stall_ms = s.i(k.stall_ms);
  c.jump_deg = s.f(k.jump_deg);
  c.move_timeout_ms = s.i(k.move_timeout_s) * 1000;
  c.speed_deg_s = s.f(k.speed_deg_s);
  c.slow_speed_ratio = s.f(k.slow_speed_ratio);
  c.pwm_dead_band = s.f(k.pwm_dead_band);
  c.coast_s = s.f(k.coast_s);
  c.coast_learn = s.b(k.coast_learn);
  c.slip_deg = s.f(Id::kSlipDeg);
  c.slip_fault = s.b(Id::kSlipFault);
  c.slip_rehold = s.b(Id::kSlipRehold);
  if (axis == AxisId::kAz) {  // an elevation axis has none of these
    c.continuous = s.b(Id::kAzContinuous);
    c.has_brake = s.b(Id::kAzHasBrake);
    c.brake_release_ms = s.i(Id::kAzBrakeReleaseMs);
    c.brake_engage_ms = s.i(Id::kAzBrakeEngageMs);
    c.mag_chip = static_cast<MagChip>(s.i(Id::kMagChip));
    c.mag_cal = {s.f(Id::kMagXMin), s.f(Id::kMagXMax),           s.f(Id::kMagYMin),
                 s.f(Id::kMagYMax), s.f(Id::kMagDeclinationDeg), s.b(Id::kMagReverse)};
    c.mag_lowpass_ms = s.i(Id::kMagLowpassMs);
  }
  return c;
}

}  // namespace rotord
