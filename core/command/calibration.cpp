#include "command/calibration.hpp"

#include "command/settings_commands.hpp"
#include "motion/angles.hpp"

namespace rotord::command {
namespace {

using settings::Id;

struct AxisKeys {
  Id min_deg, max_deg, offset_deg, sensor;
  Id lo_counts, lo_deg, hi_counts, hi_deg;
  Id ma3_zero_deg, ma3_reverse, ma3_bits;
};

constexpr AxisKeys kAz{Id::kAzMinDeg,         Id::kAzMaxDeg,         Id::kAzOffsetDeg,
                       Id::kAzSensor,         Id::kAzPotCalLoCounts, Id::kAzPotCalLoDeg,
                       Id::kAzPotCalHiCounts, Id::kAzPotCalHiDeg,    Id::kAzMa3ZeroDeg,
                       Id::kAzMa3Reverse,     Id::kAzMa3Bits};
constexpr AxisKeys kEl{Id::kElMinDeg,         Id::kElMaxDeg,         Id::kElOffsetDeg,
                       Id::kElSensor,         Id::kElPotCalLoCounts, Id::kElPotCalLoDeg,
                       Id::kElPotCalHiCounts, Id::kElPotCalHiDeg,    Id::kElMa3ZeroDeg,
                       Id::kElMa3Reverse,     Id::kElMa3Bits};

constexpr int kSensorPot = 0;  // choice indices of az.sensor / el.sensor
constexpr int kSensorMa3 = 1;

/// Sets up to two settings together, or neither: each value is range-checked
/// by the table, then the cross-setting rules must still hold.
Error set_pair(settings::Settings& s, Id a, double a_value, Id b, double b_value) {
  const double old_a = s.get(a);
  const double old_b = s.get(b);
  if (s.set(a, a_value).error == Error::kOk && s.set(b, b_value).error == Error::kOk &&
      s.check_consistency().error == Error::kOk)
    return Error::kOk;
  s.set(a, old_a);
  s.set(b, old_b);
  return Error::kOutOfRange;
}

Error set_point(Controller& controller, AxisId axis, CalPoint point) {
  const bool az = axis == AxisId::kAz;
  if (!az && !controller.has_el()) return Error::kNotSupported;
  const RotatorStatus status = controller.status();
  const AxisStatus& a = az ? status.az : status.el;
  // A raw value read from a lost, railed or frozen sensor would calibrate
  // onto noise or an old angle. (A jump fault keeps valid raw readings:
  // recalibrating is how to fix one.)
  if (!a.position_valid || a.fault == AxisFault::kSensorLost ||
      a.fault == AxisFault::kSensorRange || a.fault == AxisFault::kNoSensor ||
      a.fault == AxisFault::kSensorStuck)
    return Error::kFaulted;
  settings::Settings& s = controller.settings();
  const AxisKeys& k = az ? kAz : kEl;
  const bool offset = point == CalPoint::kLo;
  // The sensor frame excludes the user offset: position = sensor + offset.
  const double stop_deg = s.get(offset ? k.min_deg : k.max_deg) - s.get(k.offset_deg);

  switch (s.i(k.sensor)) {
    case kSensorPot:
      return offset ? set_pair(s, k.lo_counts, a.raw, k.lo_deg, stop_deg)
                    : set_pair(s, k.hi_counts, a.raw, k.hi_deg, stop_deg);
    case kSensorMa3: {
      if (!offset) return Error::kNotSupported;
      const int bits = s.i(k.ma3_bits) == 0 ? 10 : 12;
      float code_deg = a.raw * 360.0f / static_cast<float>(1 << bits);
      if (s.b(k.ma3_reverse)) code_deg = -code_deg;
      // The MA3 reads wrap_360(code_deg - zero); make that the stop's bearing.
      const float zero = wrap_360(code_deg - static_cast<float>(stop_deg));
      return s.set(k.ma3_zero_deg, zero).error == Error::kOk ? Error::kOk : Error::kOutOfRange;
    }
    default:
      return Error::kNotSupported;
  }
}

}  // namespace

Error calibrate(Controller& controller, const Origin& from, AxisId axis, CalPoint point) {
  const Error e = set_point(controller, axis, point);
  told_words(controller, from, axis == AxisId::kEl ? "cal el" : "cal az", error_name(e),
             point == CalPoint::kHi ? "hi" : "lo");
  return e;
}

}  // namespace rotord::command
