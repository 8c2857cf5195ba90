#pragma once
#include <cmath>

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

}  // namespace rotord::protocol
