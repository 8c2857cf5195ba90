#include "sensors/pot_calibration.hpp"

namespace rotord {
namespace {

float sign(float v) {
  return v > 0.0f ? 1.0f : v < 0.0f ? -1.0f : 0.0f;
}

}  // namespace

int PotCalibration::first_bad_point() const {
  if (count < 2) return count;
  const auto& p = points;
  const float counts_dir = sign(p[1].counts - p[0].counts);
  const float deg_dir = sign(p[1].deg - p[0].deg);
  if (counts_dir == 0.0f || deg_dir == 0.0f) return 1;
  for (std::size_t n = 2; n < static_cast<std::size_t>(count); ++n) {
    if (sign(p[n].counts - p[n - 1].counts) != counts_dir ||
        sign(p[n].deg - p[n - 1].deg) != deg_dir)
      return static_cast<int>(n);
  }
  return -1;
}

float PotCalibration::to_deg(float counts) const {
  // Find the segment that holds `counts`; below the first or beyond the last
  // point the end segment is extended (a rotator slightly past its
  // calibration end still reads a sensible angle). Works for tables with
  // rising or falling counts.
  const std::size_t last = static_cast<std::size_t>(count) - 1;
  const bool rising = points[last].counts > points[0].counts;
  std::size_t seg = 0;
  while (seg + 1 < last) {
    const float next = points[seg + 1].counts;
    if (rising ? counts < next : counts > next) break;
    ++seg;
  }
  const Point& a = points[seg];
  const Point& b = points[seg + 1];
  return a.deg + (counts - a.counts) * (b.deg - a.deg) / (b.counts - a.counts);
}

}  // namespace rotord
