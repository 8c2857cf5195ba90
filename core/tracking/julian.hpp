#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rotord::tracking {

/// 2000-01-01 12:00 (J2000.0) as a Julian date and as Unix milliseconds.
inline constexpr double kJulianDateJ2000 = 2451545.0;
inline constexpr std::int64_t kUnixMsJ2000 = 946'728'000'000;

/// Days since J2000.0 (UTC taken as UT1: |UT1-UTC| < 0.9 s moves GMST by
/// less than 0.004 deg, within the tolerances of rotator pointing).
inline double days_since_j2000(std::int64_t unix_ms) {
  return static_cast<double>(unix_ms - kUnixMsJ2000) / 86'400'000.0;
}

/// Greenwich mean sidereal time, radians in [0, 2 pi), IAU-82 (Vallado's
/// gstime, the one SGP4's improved mode uses), from days since J2000 UT1.
double gmst_rad(double days_j2000_ut1);

/// A TLE epoch (four-digit year, day of year with fraction) as Unix ms.
double tle_epoch_unix_ms(int year, double day_of_year);

/// A TLE epoch as SGP4's days since 1949-12-31 00:00, computed the way
/// Vallado's twoline2rv does (calendar date, then Julian date whole + fraction
/// summed in one double): the deep-space terms depend on the rounding of that
/// sum, and the verification output was made with it.
double tle_epoch_days_1950(int year, double day_of_year);

/// Parses "YYYY-MM-DDTHH:MM:SS[.fff]Z" (a space may replace the T; the Z may
/// be "+00:00" or absent) into Unix ms. False on anything else or an invalid
/// date.
bool parse_utc(std::string_view text, std::int64_t& unix_ms);

/// Writes Unix ms as "2019-12-09T16:34:30Z" (rounded to the second). Returns
/// the length, 0 when it does not fit or the year is not 0000..9999.
std::size_t format_utc_seconds(std::int64_t unix_ms, char* out, std::size_t capacity);

}  // namespace rotord::tracking
