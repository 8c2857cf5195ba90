#include "settings/pot_table.hpp"

#include "settings/axis_rows.hpp"

namespace rotord::settings {
namespace {

// The extra points are declared as (counts, deg) pairs in order
// (axis_settings.def), so point k's rows are m1_counts + 2 k and the one after.
constexpr bool mid_points_in_pairs(AxisId axis) {
  const int m1 = static_cast<int>(axis_id(axis, AxisRow::kPotCalM1Counts));
  return static_cast<int>(axis_id(axis, AxisRow::kPotCalM2Counts)) == m1 + 2 &&
         static_cast<int>(axis_id(axis, AxisRow::kPotCalM6Deg)) == m1 + 11;
}
static_assert(mid_points_in_pairs(AxisId::kAz) && mid_points_in_pairs(AxisId::kEl));

Id mid_row(AxisId axis, int k, int which) {
  return static_cast<Id>(static_cast<int>(axis_id(axis, AxisRow::kPotCalM1Counts)) + 2 * k + which);
}

}  // namespace

PotCalibration pot_calibration_from(const Settings& s, AxisId axis) {
  const auto id = [axis](AxisRow row) { return axis_id(axis, row); };
  PotCalibration c;
  c.count = 0;
  c.add(s.f(id(AxisRow::kPotCalLoCounts)), s.f(id(AxisRow::kPotCalLoDeg)));
  const int mids = s.i(id(AxisRow::kPotCalMidPoints));
  for (int k = 0; k < mids; ++k) c.add(s.f(mid_row(axis, k, 0)), s.f(mid_row(axis, k, 1)));
  c.add(s.f(id(AxisRow::kPotCalHiCounts)), s.f(id(AxisRow::kPotCalHiDeg)));
  return c;
}

const char* pot_point_key(AxisId axis, int index, int count) {
  if (index <= 0) return def(axis_id(axis, AxisRow::kPotCalLoCounts)).key;
  if (index >= count - 1) return def(axis_id(axis, AxisRow::kPotCalHiCounts)).key;
  return def(mid_row(axis, index - 1, 0)).key;
}

}  // namespace rotord::settings
