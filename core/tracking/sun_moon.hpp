#pragma once
#include <cstdint>

#include "tracking/observer.hpp"

namespace rotord::tracking {

enum class Body : std::uint8_t { kSun, kMoon };

/// Geocentric apparent position of the Sun or the Moon, km, in the true
/// equator and equinox of date. Series from Meeus, "Astronomical Algorithms"
/// (2nd ed.): the Sun from a truncated VSOP87 (appendix III, about 0.001
/// deg), the Moon from chapter 47 with its main terms (tables 47.A and 47.B:
/// every longitude/distance term, the 30 largest latitude terms), nutation in
/// longitude and obliquity from chapter 22's short series. `days_j2000_tt` is
/// Terrestrial Time.
void body_position_tod(Body body, double days_j2000_tt, double r_km[3]);

/// Greenwich apparent sidereal time: GMST plus the equation of the equinoxes
/// (nutation in longitude times cos obliquity), radians.
double gast_rad(double days_j2000_ut1);

/// TT - UTC, seconds: 32.184 + 37 leap seconds as of 2017 (UT1 ~ UTC). The
/// Moon moves 0.0002 deg per second of error.
inline constexpr double kTtMinusUtc_s = 69.184;

/// The body's Earth-fixed position and velocity at `unix_ms` (UTC taken as
/// UT1; the velocity, for rates, from the Earth's rotation and the body's mean
/// motion along the ecliptic).
EcefState body_ecef(Body body, std::int64_t unix_ms);

}  // namespace rotord::tracking
