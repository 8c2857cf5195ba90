#include "util/utc_time.hpp"

#include <cstdio>

namespace rotord {
namespace {

/// Floor division: -1 ms is 1969-12-31T23:59:59.999.
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0);
}

}  // namespace

std::size_t format_utc_iso8601(std::int64_t unix_ms, char* out, std::size_t capacity) {
  const std::int64_t days = floor_div(unix_ms, 86'400'000);
  const std::int64_t ms_of_day = unix_ms - days * 86'400'000;
  // civil_from_days (H. Hinnant, public domain): days since 1970-01-01 to
  // year, month, day in the proleptic Gregorian calendar.
  const std::int64_t z = days + 719'468;
  const std::int64_t era = floor_div(z, 146'097);
  const std::int64_t doe = z - era * 146'097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36'524 - doe / 146'096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const std::int64_t day = doy - (153 * mp + 2) / 5 + 1;
  const std::int64_t month = mp < 10 ? mp + 3 : mp - 9;
  const std::int64_t year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  if (year < 0 || year > 9999) return 0;
  const int n = std::snprintf(
      out, capacity, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", static_cast<int>(year),
      static_cast<int>(month), static_cast<int>(day), static_cast<int>(ms_of_day / 3'600'000),
      static_cast<int>(ms_of_day / 60'000 % 60), static_cast<int>(ms_of_day / 1000 % 60),
      static_cast<int>(ms_of_day % 1000));
  if (n < 0 || static_cast<std::size_t>(n) >= capacity) return 0;
  return static_cast<std::size_t>(n);
}

}  // namespace rotord
