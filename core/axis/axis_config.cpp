#include "axis/axis_config.hpp"

#include "settings/axis_rows.hpp"
#include "settings/pot_table.hpp"

namespace rotord {

using settings::AxisRow;
using settings::Id;

AxisConfig axis_config_from(const settings::Settings& s, AxisId axis) {
  // The one mapping from the per-axis rows (settings/axis_settings.def) to
  // the fields, for either axis; the azimuth-only rows are read below.
  // One reader per type, so each field costs the M0+ a call, not a lookup.
  const auto f = [&s, axis](AxisRow row) { return s.f(settings::axis_id(axis, row)); };
  const auto i = [&s, axis](AxisRow row) { return s.i(settings::axis_id(axis, row)); };
  const auto b = [&s, axis](AxisRow row) { return s.b(settings::axis_id(axis, row)); };
  AxisConfig c;
  c.min_deg = f(AxisRow::kMinDeg);
  c.max_deg = f(AxisRow::kMaxDeg);
  c.offset_deg = f(AxisRow::kOffsetDeg);
  c.tolerance_deg = f(AxisRow::kToleranceDeg);
  c.slow_zone_deg = f(AxisRow::kSlowZoneDeg);
  c.drive = static_cast<DriveType>(i(AxisRow::kDrive));
  c.dir_settle_ms = i(AxisRow::kDirSettleMs);
  c.soft_ms = i(AxisRow::kSoftMs);
  c.reverse_dead_ms = i(AxisRow::kReverseDeadMs);
  c.min_dwell_ms = i(AxisRow::kMinDwellMs);
  c.pwm_slow_duty = f(AxisRow::kPwmSlowDuty);
  c.pwm_fast_duty = f(AxisRow::kPwmFastDuty);
  c.sensor = static_cast<SensorType>(i(AxisRow::kSensor));
  c.pot_cal = settings::pot_calibration_from(s, axis);
  c.pot_filter = {i(AxisRow::kPotSamples), b(AxisRow::kPotMedian), i(AxisRow::kPotLowpassMs)};
  c.ma3_zero_deg = f(AxisRow::kMa3ZeroDeg);
  c.ma3_reverse = b(AxisRow::kMa3Reverse);
  c.ma3_bits = i(AxisRow::kMa3Bits) == 0 ? 10 : 12;
  c.stall_deg = f(AxisRow::kStallDeg);
  c.stall_ms = i(AxisRow::kStallMs);
  c.jump_deg = f(AxisRow::kJumpDeg);
  c.move_timeout_ms = i(AxisRow::kMoveTimeoutS) * 1000;
  c.speed_deg_s = f(AxisRow::kSpeedDegS);
  c.slow_speed_ratio = f(AxisRow::kSlowSpeedRatio);
  c.pwm_dead_band = f(AxisRow::kPwmDeadBand);
  c.coast_s = f(AxisRow::kCoastS);
  c.coast_learn = b(AxisRow::kCoastLearn);
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
