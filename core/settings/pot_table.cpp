#include "settings/pot_table.hpp"

namespace rotord::settings {
namespace {

struct AxisRows {
  Id lo_counts, lo_deg, hi_counts, hi_deg, mid_points, m1_counts;
};

// The extra points are declared as (counts, deg) pairs in order, so point k's
// rows are m1_counts + 2 (k - 1) and the one after.
static_assert(static_cast<int>(Id::kAzPotCalM6Deg) - static_cast<int>(Id::kAzPotCalM1Counts) == 11);
static_assert(static_cast<int>(Id::kElPotCalM6Deg) - static_cast<int>(Id::kElPotCalM1Counts) == 11);
static_assert(static_cast<int>(Id::kAzPotCalM2Counts) - static_cast<int>(Id::kAzPotCalM1Counts) ==
              2);
static_assert(static_cast<int>(Id::kElPotCalM2Counts) - static_cast<int>(Id::kElPotCalM1Counts) ==
              2);

AxisRows rows(AxisId axis) {
  if (axis == AxisId::kAz)
    return {Id::kAzPotCalLoCounts, Id::kAzPotCalLoDeg,     Id::kAzPotCalHiCounts,
            Id::kAzPotCalHiDeg,    Id::kAzPotCalMidPoints, Id::kAzPotCalM1Counts};
  return {Id::kElPotCalLoCounts, Id::kElPotCalLoDeg,     Id::kElPotCalHiCounts,
          Id::kElPotCalHiDeg,    Id::kElPotCalMidPoints, Id::kElPotCalM1Counts};
}

Id mid_row(const AxisRows& r, int k, int which) {
  return static_cast<Id>(static_cast<int>(r.m1_counts) + 2 * k + which);
}

}  // namespace

PotCalibration pot_calibration_from(const Settings& s, AxisId axis) {
  const AxisRows r = rows(axis);
  PotCalibration c;
  c.count = 0;
  c.add(s.f(r.lo_counts), s.f(r.lo_deg));
  const int mids = s.i(r.mid_points);
  for (int k = 0; k < mids; ++k) c.add(s.f(mid_row(r, k, 0)), s.f(mid_row(r, k, 1)));
  c.add(s.f(r.hi_counts), s.f(r.hi_deg));
  return c;
}

const char* pot_point_key(AxisId axis, int index, int count) {
  const AxisRows r = rows(axis);
  if (index <= 0) return def(r.lo_counts).key;
  if (index >= count - 1) return def(r.hi_counts).key;
  return def(mid_row(r, index - 1, 0)).key;
}

}  // namespace rotord::settings
