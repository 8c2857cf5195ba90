#include "tracking/julian.hpp"

#include <cmath>
#include <cstdio>

#include "util/civil_date.hpp"
#include "util/slice.hpp"

namespace rotord::tracking {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool is_leap(int year) {
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int days_in_month(int year, int month) {
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && is_leap(year) ? 29 : kDays[month - 1];
}

bool digits(std::string_view s, std::size_t at, std::size_t n, int& out) {
  if (at + n > s.size()) return false;
  int v = 0;
  for (std::size_t i = at; i < at + n; ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    v = v * 10 + (s[i] - '0');
  }
  out = v;
  return true;
}

}  // namespace

double gmst_rad(double days_j2000_ut1) {
  const double tut1 = days_j2000_ut1 / 36525.0;
  double temp = -6.2e-6 * tut1 * tut1 * tut1 + 0.093104 * tut1 * tut1 +
                (876600.0 * 3600 + 8640184.812866) * tut1 + 67310.54841;  // seconds of time
  temp = std::fmod(temp * (kPi / 180.0) / 240.0, 2.0 * kPi);
  if (temp < 0.0) temp += 2.0 * kPi;
  return temp;
}

double tle_epoch_unix_ms(int year, double day_of_year) {
  return static_cast<double>(days_from_civil(year, 1, 1)) * 86'400'000.0 +
         (day_of_year - 1.0) * 86'400'000.0;
}

double tle_epoch_days_1950(int year, double day_of_year) {
  // days2mdhms: day of year to month, day, hours, minutes, seconds.
  const int whole_day = static_cast<int>(std::floor(day_of_year));
  int month = 1;
  int before = 0;
  while (month < 12 && whole_day > before + days_in_month(year, month)) {
    before += days_in_month(year, month);
    ++month;
  }
  const int day = whole_day - before;
  double temp = (day_of_year - whole_day) * 24.0;
  const int hr = static_cast<int>(std::floor(temp));
  temp = (temp - hr) * 60.0;
  const int minute = static_cast<int>(std::floor(temp));
  const double sec = (temp - minute) * 60.0;
  // jday: Julian date of the calendar date, plus the day fraction.
  const double jd = 367.0 * year -
                    std::floor((7 * (year + std::floor((month + 9) / 12.0))) * 0.25) +
                    std::floor(275 * month / 9.0) + day + 1721013.5;
  double jd_frac = (sec + minute * 60.0 + hr * 3600.0) / 86400.0;
  double jd_whole = jd;
  if (std::fabs(jd_frac) > 1.0) {
    const double whole = std::floor(jd_frac);
    jd_whole += whole;
    jd_frac -= whole;
  }
  return (jd_whole + jd_frac) - 2433281.5;
}

bool parse_utc(std::string_view s, std::int64_t& unix_ms) {
  int year, month, day, hour, minute, second;
  if (!digits(s, 0, 4, year) || s.size() < 19 || s[4] != '-' || !digits(s, 5, 2, month) ||
      s[7] != '-' || !digits(s, 8, 2, day) || (s[10] != 'T' && s[10] != 't' && s[10] != ' ') ||
      !digits(s, 11, 2, hour) || s[13] != ':' || !digits(s, 14, 2, minute) || s[16] != ':' ||
      !digits(s, 17, 2, second))
    return false;
  std::size_t at = 19;
  int ms = 0;
  if (at < s.size() && s[at] == '.') {
    ++at;
    int scale = 100;
    const std::size_t first = at;
    while (at < s.size() && s[at] >= '0' && s[at] <= '9') {
      ms += (s[at] - '0') * scale;
      scale /= 10;
      ++at;
    }
    if (at == first) return false;
  }
  const std::string_view zone = text::slice(s, at);
  if (!(zone.empty() || zone == "Z" || zone == "z" || zone == "+00:00")) return false;
  if (month < 1 || month > 12 || day < 1 || day > days_in_month(year, month) || hour > 23 ||
      minute > 59 || second > 59)
    return false;
  unix_ms =
      ((days_from_civil(year, month, day) * 24 + hour) * 60 + minute) * 60'000 + second * 1000 + ms;
  return true;
}

std::size_t format_utc_seconds(std::int64_t unix_ms, char* out, std::size_t capacity) {
  const std::int64_t s = floor_div(unix_ms + 500, 1000);
  const std::int64_t days = floor_div(s, 86'400);
  const std::int64_t sod = s - days * 86'400;
  const CivilDate date = civil_from_days(days);
  if (date.year < 0 || date.year > 9999) return 0;
  const int n =
      std::snprintf(out, capacity, "%04d-%02d-%02dT%02d:%02d:%02dZ", static_cast<int>(date.year),
                    date.month, date.day, static_cast<int>(sod / 3600),
                    static_cast<int>(sod / 60 % 60), static_cast<int>(sod % 60));
  if (n < 0 || static_cast<std::size_t>(n) >= capacity) return 0;
  return static_cast<std::size_t>(n);
}

}  // namespace rotord::tracking
