#pragma once
// Reads the reference CSVs compiled into the unit tests (cmake/EmbedTextLines.cmake).
#include <cstddef>
#include <string_view>

#include "util/text.hpp"

namespace rotord::test {

/// Splits one CSV line (no quoting) into at most `max` fields; returns the count.
inline std::size_t csv_fields(std::string_view line, std::string_view* out, std::size_t max) {
  std::size_t n = 0;
  while (n < max) {
    const std::size_t comma = line.find(',');
    out[n++] = line.substr(0, comma);
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  return n;
}

inline double csv_number(std::string_view field) {
  double v = 0.0;
  return text::parse_double(field, v) ? v : -1e300;
}

/// The smallest angle between two bearings, degrees.
inline double bearing_difference_deg(double a, double b) {
  double d = a - b;
  while (d > 180.0) d -= 360.0;
  while (d < -180.0) d += 360.0;
  return d < 0.0 ? -d : d;
}

}  // namespace rotord::test
