#include "util/utc_time.hpp"

#include <cstdio>

#include "util/civil_date.hpp"

namespace rotord {

std::size_t format_utc_iso8601(std::int64_t unix_ms, char* out, std::size_t capacity) {
  const std::int64_t days = floor_div(unix_ms, 86'400'000);
  const std::int64_t ms_of_day = unix_ms - days * 86'400'000;
  const CivilDate date = civil_from_days(days);
  if (date.year < 0 || date.year > 9999) return 0;
  const int n = std::snprintf(
      out, capacity, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", static_cast<int>(date.year), date.month,
      date.day, static_cast<int>(ms_of_day / 3'600'000), static_cast<int>(ms_of_day / 60'000 % 60),
      static_cast<int>(ms_of_day / 1000 % 60), static_cast<int>(ms_of_day % 1000));
  if (n < 0 || static_cast<std::size_t>(n) >= capacity) return 0;
  return static_cast<std::size_t>(n);
}

}  // namespace rotord
