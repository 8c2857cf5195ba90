#pragma once
#include <cmath>

#include "motion/angles.hpp"
#include "rotator/controller.hpp"

namespace rotord::protocol {

// A reading for "%.1f" / "%.2f" without a "-0.0": a sensor a hair below zero
// (noise at a 0 deg end stop) prints as 0, as every client expects to parse
// and show it.
inline double one_decimal(float deg) {
  const double d = static_cast<double>(deg);
  return std::fabs(d) < 0.05 ? 0.0 : d;
}

inline double two_decimals(float deg) {
  const double d = static_cast<double>(deg);
  return std::fabs(d) < 0.005 ? 0.0 : d;
}

/// A compass bearing rounded to `decimals` (1 or 2) places before it is
/// printed: 359.97 is 0.0, never 360.0, which bearing-only clients refuse.
inline double bearing_rounded(float deg, int decimals) {
  const double scale = decimals == 1 ? 10.0 : 100.0;
  const double rounded = std::round(static_cast<double>(wrap_360(deg)) * scale) / scale;
  return rounded >= 360.0 ? 0.0 : rounded;
}

/// The azimuth as WRC, rotctld and seed print it: the unwrapped position, or
/// on an endless axis (whose status is a bearing) the rounded bearing.
inline double az_reading(const RotatorStatus& s, int decimals) {
  if (s.limits.az_continuous) return bearing_rounded(s.az.position_deg, decimals);
  return decimals == 1 ? one_decimal(s.az.position_deg) : two_decimals(s.az.position_deg);
}

}  // namespace rotord::protocol
