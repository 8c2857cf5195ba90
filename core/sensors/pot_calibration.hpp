#pragma once
#include <array>
#include <cstddef>

namespace rotord {

/// Potentiometer calibration: ADC counts read at known angles, interpolated
/// linearly between neighbouring points and extrapolated along the end
/// segments. Two points is the classic linear calibration; more points follow
/// a pot whose track is not linear (Hy-Gain meters, worn G-5500 pots).
struct PotCalibration {
  static constexpr int kMaxPoints = 8;
  struct Point {
    float counts = 0.0f;
    float deg = 0.0f;
  };

  std::array<Point, kMaxPoints> points{{{0.0f, 0.0f}, {4095.0f, 360.0f}}};
  int count = 2;

  static PotCalibration two_point(float counts_lo, float deg_lo, float counts_hi, float deg_hi) {
    PotCalibration c;
    c.points[0] = {counts_lo, deg_lo};
    c.points[1] = {counts_hi, deg_hi};
    c.count = 2;
    return c;
  }

  /// Appends a point (ignored beyond kMaxPoints; valid() then still checks
  /// the points that were kept).
  void add(float counts, float deg) {
    if (count < kMaxPoints) points[static_cast<std::size_t>(count++)] = {counts, deg};
  }

  /// Index of the first point that breaks the order (counts strictly rising
  /// or strictly falling from the first point on, degrees strictly rising or
  /// falling the same way for every pair), or -1 when the table is usable.
  /// A table with fewer than two points fails at index `count`.
  int first_bad_point() const;
  bool valid() const { return first_bad_point() < 0; }

  /// Degrees for a (filtered, fractional) count value. Only meaningful for a
  /// valid table.
  float to_deg(float counts) const;
};

}  // namespace rotord
