#pragma once
// WGS-72, the gravity model TLEs are fitted with (Vallado et al. 2006, getgravconst).
#include <cmath>

namespace rotord::tracking::wgs72 {

inline constexpr double kMu_km3_s2 = 398600.8;
inline constexpr double kRadius_km = 6378.135;
inline constexpr double kJ2 = 0.001082616;
inline constexpr double kJ3 = -0.00000253881;
inline constexpr double kJ4 = -0.00000165597;

/// sqrt(mu) in earth radii^1.5 per minute.
inline double kXke() {
  return 60.0 / std::sqrt(kRadius_km * kRadius_km * kRadius_km / kMu_km3_s2);
}

}  // namespace rotord::tracking::wgs72
