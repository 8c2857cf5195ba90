#pragma once
// The one pointing error every bench figure and the sim scenarios use: the
// angle on the sky between where the antenna points and where the target
// is. Axis angles are turned into unit vectors (east, north, up), so an
// antenna over the top (el > 90: it looks at az + 180, 180 - el) needs no
// special case, and near the zenith an azimuth error counts only as much
// sky as it moves the beam (cos el of it), never as a per-axis figure.
#include <cmath>

namespace rotord::bench {

inline double sky_angle_deg(double ant_az_deg, double ant_el_deg, double az_deg, double el_deg) {
  constexpr double kRad = 3.14159265358979323846 / 180.0;
  const double a_az = ant_az_deg * kRad, a_el = ant_el_deg * kRad;
  const double b_az = az_deg * kRad, b_el = el_deg * kRad;
  const double ax = std::cos(a_el) * std::sin(a_az), ay = std::cos(a_el) * std::cos(a_az);
  const double bx = std::cos(b_el) * std::sin(b_az), by = std::cos(b_el) * std::cos(b_az);
  const double az_up = std::sin(a_el), bz_up = std::sin(b_el);
  // atan2 of the cross and dot products: accurate for small angles too,
  // where acos of a dot product near 1 loses the digits that matter here.
  const double cx = ay * bz_up - az_up * by, cy = az_up * bx - ax * bz_up, cz = ax * by - ay * bx;
  const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double dot = ax * bx + ay * by + az_up * bz_up;
  return std::atan2(cross, dot) / kRad;
}

}  // namespace rotord::bench
