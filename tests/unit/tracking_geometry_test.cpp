// Observer geometry against reference values made by
// tests/data/tracking/make_reference.py (skyfield, python-sgp4, PyEphem; the
// tests themselves need no Python): satellites through TEME -> GMST -> WGS-84
// look angles, the Sun and the Moon topocentric. Tolerances are issue 13's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string_view>

#include "csv_rows.hpp"
#include "tracking/julian.hpp"
#include "tracking/sky_target.hpp"

extern const char* const kSatellitesCsv[];
extern const unsigned long kSatellitesCsv_count;
extern const char* const kSunMoonCsv[];
extern const unsigned long kSunMoonCsv_count;

namespace rotord::tracking {
namespace {

using test::bearing_difference_deg;
using test::csv_fields;
using test::csv_number;

struct NamedTle {
  const char* name;
  const char* line1;
  const char* line2;
};
// The same elements as make_reference.py.
constexpr NamedTle kTles[] = {
    {"ISS", "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
     "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482"},
    {"MOLNIYA", "1 08195U 75081A   06176.33215444  .00000099  00000-0  11873-3 0   813",
     "2 08195  64.1586 279.0717 6877146 264.7651  20.2257  2.00491383225656"},
    {"XM3", "1 28626U 05008A   06176.46683397 -.00000205  00000-0  10000-3 0  2190",
     "2 28626   0.0019 286.9433 0000335  13.7918  55.6504  1.00270176  4891"},
};

/// Azimuth is judged below 80 deg elevation: near the zenith it is ill-conditioned.
constexpr double kAzimuthJudgedBelowDeg = 80.0;

struct MaxError {
  double az = 0, el = 0;
  void add_az(double d) { az = std::fmax(az, d); }
  void add_el(double d) { el = std::fmax(el, d); }
};

TEST(TrackingGeometryTest, SatelliteLookAnglesMatchTheSameChainAndSkyfield) {
  SkyTarget targets[std::size(kTles)];
  for (std::size_t i = 0; i < std::size(kTles); ++i) {
    Tle tle;
    ASSERT_TRUE(parse_tle(kTles[i].line1, kTles[i].line2, tle).ok()) << kTles[i].name;
    ASSERT_EQ(targets[i].set_satellite(tle), Sgp4Error::kOk);
  }
  MaxError simple, skyfield;
  double max_range_km = 0, max_range_rate_km_s = 0, max_range_skyfield_km = 0;
  int rows = 0;
  for (unsigned long line = 1; line < kSatellitesCsv_count; ++line) {
    std::string_view f[12];
    ASSERT_EQ(csv_fields(kSatellitesCsv[line], f, 12), 12u) << kSatellitesCsv[line];
    std::size_t which = 0;
    while (which < std::size(kTles) && f[0] != kTles[which].name) ++which;
    ASSERT_LT(which, std::size(kTles)) << f[0];
    std::int64_t when = 0;
    ASSERT_TRUE(parse_utc(f[1], when)) << f[1];
    const Observer observer(Geodetic{csv_number(f[2]), csv_number(f[3]), csv_number(f[4])});
    LookAngles look;
    ASSERT_EQ(targets[which].look(when, observer, look), Sgp4Error::kOk);
    ++rows;

    const double el_simple = csv_number(f[6]);
    simple.add_el(std::fabs(look.el_deg - el_simple));
    skyfield.add_el(std::fabs(look.el_deg - csv_number(f[10])));
    if (el_simple < kAzimuthJudgedBelowDeg) {
      simple.add_az(bearing_difference_deg(look.az_deg, csv_number(f[5])));
      skyfield.add_az(bearing_difference_deg(look.az_deg, csv_number(f[9])));
    }
    max_range_km = std::fmax(max_range_km, std::fabs(look.range_km - csv_number(f[7])));
    max_range_rate_km_s =
        std::fmax(max_range_rate_km_s, std::fabs(look.range_rate_km_s - csv_number(f[8])));
    max_range_skyfield_km =
        std::fmax(max_range_skyfield_km, std::fabs(look.range_km - csv_number(f[11])));
  }
  std::printf(
      "satellites, %d points: vs same chain az %.2g el %.2g deg, range %.2g km, rate %.2g km/s; "
      "vs skyfield az %.3f el %.3f deg, range %.3f km\n",
      rows, simple.az, simple.el, max_range_km, max_range_rate_km_s, skyfield.az, skyfield.el,
      max_range_skyfield_km);
  EXPECT_GT(rows, 700);
  EXPECT_LT(simple.az, 0.01);
  EXPECT_LT(simple.el, 0.01);
  EXPECT_LT(max_range_km, 0.01);
  EXPECT_LT(max_range_rate_km_s, 1e-5);
  EXPECT_LT(skyfield.az, 0.06);
  EXPECT_LT(skyfield.el, 0.03);
  EXPECT_LT(max_range_skyfield_km, 0.5);
}

TEST(TrackingGeometryTest, SunAndMoonWithinTheirTolerancesOfPyEphem) {
  MaxError sun, moon;
  int rows = 0;
  for (unsigned long line = 1; line < kSunMoonCsv_count; ++line) {
    std::string_view f[7];
    ASSERT_EQ(csv_fields(kSunMoonCsv[line], f, 7), 7u) << kSunMoonCsv[line];
    std::int64_t when = 0;
    ASSERT_TRUE(parse_utc(f[1], when)) << f[1];
    const Observer observer(Geodetic{csv_number(f[2]), csv_number(f[3]), csv_number(f[4])});
    SkyTarget body;
    body.set_body(f[0] == "sun" ? Body::kSun : Body::kMoon);
    LookAngles look;
    ASSERT_EQ(body.look(when, observer, look), Sgp4Error::kOk);
    MaxError& max = f[0] == "sun" ? sun : moon;
    const double el = csv_number(f[6]);
    max.add_el(std::fabs(look.el_deg - el));
    if (el < kAzimuthJudgedBelowDeg)
      max.add_az(bearing_difference_deg(look.az_deg, csv_number(f[5])));
    ++rows;
  }
  std::printf("%d points: Sun az %.4f el %.4f deg, Moon az %.4f el %.4f deg\n", rows, sun.az,
              sun.el, moon.az, moon.el);
  EXPECT_EQ(rows, 800);
  EXPECT_LT(sun.az, 0.02);
  EXPECT_LT(sun.el, 0.02);
  EXPECT_LT(moon.az, 0.05);
  EXPECT_LT(moon.el, 0.05);
}

/// Rates from the velocity against a central difference of the angles.
void expect_rates_match_differences(SkyTarget& target, const Observer& observer, std::int64_t when,
                                    std::int64_t half_ms, double tolerance, double abs_deg_s,
                                    bool range_rate_too) {
  LookAngles now, before, after;
  ASSERT_EQ(target.look(when, observer, now), Sgp4Error::kOk);
  ASSERT_EQ(target.look(when - half_ms, observer, before), Sgp4Error::kOk);
  ASSERT_EQ(target.look(when + half_ms, observer, after), Sgp4Error::kOk);
  const double dt_s = 2.0 * static_cast<double>(half_ms) / 1000.0;
  double daz = after.az_deg - before.az_deg;
  if (daz > 180.0) daz -= 360.0;
  if (daz < -180.0) daz += 360.0;
  const double az_rate = daz / dt_s, el_rate = (after.el_deg - before.el_deg) / dt_s;
  const double range_rate = (after.range_km - before.range_km) / dt_s;
  EXPECT_NEAR(now.az_rate_deg_s, az_rate, tolerance * std::fabs(az_rate) + abs_deg_s) << when;
  EXPECT_NEAR(now.el_rate_deg_s, el_rate, tolerance * std::fabs(el_rate) + abs_deg_s) << when;
  if (range_rate_too) {
    EXPECT_NEAR(now.range_rate_km_s, range_rate, tolerance * std::fabs(range_rate) + 1e-4) << when;
  }
}

TEST(TrackingGeometryTest, RatesAgreeWithTheChangeOfTheAngles) {
  Tle tle;
  ASSERT_TRUE(parse_tle(kTles[0].line1, kTles[0].line2, tle).ok());
  SkyTarget iss, sun, moon;
  ASSERT_EQ(iss.set_satellite(tle), Sgp4Error::kOk);
  sun.set_body(Body::kSun);
  moon.set_body(Body::kMoon);
  const Observer boulder(Geodetic{40.015, -105.27, 1655.0});
  std::int64_t pass = 0;
  ASSERT_TRUE(parse_utc("2019-12-09T17:56:00Z", pass));  // the ISS is up, 30 deg
  for (int i = 0; i < 6; ++i)
    expect_rates_match_differences(iss, boulder, pass + i * 20'000, 100, 0.002, 1e-6, true);
  // Sun and Moon: their own motion at its mean rate along the ecliptic, within
  // 2e-5 deg/s (0.07 deg/h); no radial part, so no range rate check.
  for (int i = 0; i < 6; ++i) {
    expect_rates_match_differences(sun, boulder, pass + i * 3'600'000, 30'000, 0.0, 2e-5, false);
    expect_rates_match_differences(moon, boulder, pass + i * 3'600'000, 30'000, 0.0, 2e-5, false);
  }
}

TEST(TrackingGeometryTest, ObserverOnTheEquatorSeesTheZenithStraightUp) {
  // A point 1000 km above (0 N, 0 E) in the Earth-fixed frame.
  const Observer observer(Geodetic{0, 0, 0});
  EcefState above;
  above.r_km[0] = 6378.137 + 1000.0;
  above.v_km_s[1] = 1.0;  // moving east
  const LookAngles look = observer.look(above);
  EXPECT_NEAR(look.el_deg, 90.0, 1e-9);
  EXPECT_NEAR(look.range_km, 1000.0, 1e-9);
  EXPECT_NEAR(look.range_rate_km_s, 0.0, 1e-12);
  // Due north, low: azimuth 0; due east: 90.
  EcefState north;
  north.r_km[0] = 6378.137;
  north.r_km[2] = 100.0;
  EXPECT_NEAR(observer.look(north).az_deg, 0.0, 1e-9);
  EcefState east;
  east.r_km[0] = 6378.137;
  east.r_km[1] = 100.0;
  EXPECT_NEAR(observer.look(east).az_deg, 90.0, 1e-9);
}

TEST(TrackingGeometryTest, AnEmptyTargetSaysSo) {
  SkyTarget none;
  LookAngles look;
  EXPECT_EQ(none.look(0, Observer{}, look), Sgp4Error::kNoTarget);
}

}  // namespace
}  // namespace rotord::tracking
