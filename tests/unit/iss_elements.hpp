#pragma once
// The ISS (ZARYA) elements of 2019-12-09, the example of python-sgp4's
// README, that the tracking tests compute their passes from (the pass
// through north over Boulder, 22:3x UTC, among them).
#include <cstddef>
#include <string>

namespace rotord::testing {

constexpr const char* kIssLine1 =
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991";
constexpr const char* kIssLine2 =
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482";

/// The ISS's elements as a TLE store takes them: name line and both lines.
inline std::string iss_tle_text() {
  return std::string("ISS (ZARYA)\n") + kIssLine1 + "\n" + kIssLine2 + "\n";
}

/// A line of the ISS's elements under catalog number 99999, its checksum
/// redone: a second object on the same orbit, as a docked vehicle is.
inline std::string twin_line(const char* line) {
  std::string s(line);
  s.replace(2, 5, "99999");
  int sum = 0;
  for (std::size_t i = 0; i < 68; ++i) {
    if (s[i] >= '0' && s[i] <= '9') sum += s[i] - '0';
    if (s[i] == '-') sum += 1;
  }
  s[68] = static_cast<char>('0' + sum % 10);
  return s;
}

/// The twin's elements as a TLE store takes them.
inline std::string twin_tle_text() {
  return "TWIN\n" + twin_line(kIssLine1) + "\n" + twin_line(kIssLine2) + "\n";
}

}  // namespace rotord::testing
