#include "axis/axis_config.hpp"

#include "settings/pot_table.hpp"

namespace rotord {

using settings::Id;

AxisConfig axis_config_from(const settings::Settings& s, AxisId axis) {
  AxisConfig c;
  if (axis == AxisId::kAz) {
    c.min_deg = s.f(Id::kAzMinDeg);
    c.max_deg = s.f(Id::kAzMaxDeg);
    c.continuous = s.b(Id::kAzContinuous);
    c.offset_deg = s.f(Id::kAzOffsetDeg);
    c.tolerance_deg = s.f(Id::kAzToleranceDeg);
    c.slow_zone_deg = s.f(Id::kAzSlowZoneDeg);
    c.drive = static_cast<DriveType>(s.i(Id::kAzDrive));
    c.has_brake = s.b(Id::kAzHasBrake);
    c.brake_release_ms = s.i(Id::kAzBrakeReleaseMs);
    c.brake_engage_ms = s.i(Id::kAzBrakeEngageMs);
    c.dir_settle_ms = s.i(Id::kAzDirSettleMs);
    c.soft_ms = s.i(Id::kAzSoftMs);
    c.reverse_dead_ms = s.i(Id::kAzReverseDeadMs);
    c.min_dwell_ms = s.i(Id::kAzMinDwellMs);
    c.pwm_slow_duty = s.f(Id::kAzPwmSlowDuty);
    c.pwm_fast_duty = s.f(Id::kAzPwmFastDuty);
    c.sensor = static_cast<SensorType>(s.i(Id::kAzSensor));
    c.pot_cal = settings::pot_calibration_from(s, axis);
    c.pot_filter = {s.i(Id::kAzPotSamples), s.b(Id::kAzPotMedian), s.i(Id::kAzPotLowpassMs)};
    c.ma3_zero_deg = s.f(Id::kAzMa3ZeroDeg);
    c.ma3_reverse = s.b(Id::kAzMa3Reverse);
    c.ma3_bits = s.i(Id::kAzMa3Bits) == 0 ? 10 : 12;
    c.mag_chip = static_cast<MagChip>(s.i(Id::kMagChip));
    c.mag_cal = {s.f(Id::kMagXMin), s.f(Id::kMagXMax),           s.f(Id::kMagYMin),
                 s.f(Id::kMagYMax), s.f(Id::kMagDeclinationDeg), s.b(Id::kMagReverse)};
    c.mag_lowpass_ms = s.i(Id::kMagLowpassMs);
    c.stall_deg = s.f(Id::kAzStallDeg);
    c.stall_ms = s.i(Id::kAzStallMs);
    c.jump_deg = s.f(Id::kAzJumpDeg);
    c.move_timeout_ms = s.i(Id::kAzMoveTimeoutS) * 1000;
    c.coast_s = s.f(Id::kAzCoastS);
    c.coast_learn = s.b(Id::kAzCoastLearn);
  } else {
    c.min_deg = s.f(Id::kElMinDeg);
    c.max_deg = s.f(Id::kElMaxDeg);
    c.offset_deg = s.f(Id::kElOffsetDeg);
    c.tolerance_deg = s.f(Id::kElToleranceDeg);
    c.slow_zone_deg = s.f(Id::kElSlowZoneDeg);
    c.drive = static_cast<DriveType>(s.i(Id::kElDrive));
    c.dir_settle_ms = s.i(Id::kElDirSettleMs);
    c.soft_ms = s.i(Id::kElSoftMs);
    c.reverse_dead_ms = s.i(Id::kElReverseDeadMs);
    c.min_dwell_ms = s.i(Id::kElMinDwellMs);
    c.pwm_slow_duty = s.f(Id::kElPwmSlowDuty);
    c.pwm_fast_duty = s.f(Id::kElPwmFastDuty);
    c.sensor = static_cast<SensorType>(s.i(Id::kElSensor));
    c.pot_cal = settings::pot_calibration_from(s, axis);
    c.pot_filter = {s.i(Id::kElPotSamples), s.b(Id::kElPotMedian), s.i(Id::kElPotLowpassMs)};
    c.ma3_zero_deg = s.f(Id::kElMa3ZeroDeg);
    c.ma3_reverse = s.b(Id::kElMa3Reverse);
    c.ma3_bits = s.i(Id::kElMa3Bits) == 0 ? 10 : 12;
    c.stall_deg = s.f(Id::kElStallDeg);
    c.stall_ms = s.i(Id::kElStallMs);
    c.jump_deg = s.f(Id::kElJumpDeg);
    c.move_timeout_ms = s.i(Id::kElMoveTimeoutS) * 1000;
    c.coast_s = s.f(Id::kElCoastS);
    c.coast_learn = s.b(Id::kElCoastLearn);
  }
  return c;
}

}  // namespace rotord
