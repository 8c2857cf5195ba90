#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tracking/julian.hpp"
#include "util/civil_date.hpp"

namespace rotord::tracking {
namespace {

constexpr double kRad2Deg = 180.0 / 3.14159265358979323846;

TEST(TrackingTimeTest, GmstIsTheIau82ValueAtJ2000AndTurnsOncePerSiderealDay) {
  // 18h 41m 50.54841s at J2000.0 (the constant term of the IAU-82 expression).
  EXPECT_NEAR(gmst_rad(0.0) * kRad2Deg, 280.46061837504, 1e-9);
  // 360.98564736629 deg per solar day (its linear term), mod 360.
  const double one_day =
      std::fmod(gmst_rad(1.0) * kRad2Deg - gmst_rad(0.0) * kRad2Deg + 360.0, 360.0);
  EXPECT_NEAR(one_day, 0.98564736629, 1e-8);
  EXPECT_GE(gmst_rad(-12345.678), 0.0);
  EXPECT_LT(gmst_rad(-12345.678), 2.0 * 3.14159265358979323846);
}

TEST(TrackingTimeTest, ParsesAndPrintsUtc) {
  std::int64_t ms = 0;
  ASSERT_TRUE(parse_utc("2019-12-09T16:34:30Z", ms));
  EXPECT_EQ(ms, 1'575'909'270'000);
  ASSERT_TRUE(parse_utc("2019-12-09 16:34:30.25", ms));
  EXPECT_EQ(ms, 1'575'909'270'250);
  ASSERT_TRUE(parse_utc("2000-01-01T12:00:00+00:00", ms));
  EXPECT_EQ(ms, kUnixMsJ2000);
  ASSERT_TRUE(parse_utc("2024-02-29T00:00:00Z", ms));  // a leap day
  for (const char* bad : {"", "2019-12-09", "2019-12-09T16:34Z", "2019-13-09T16:34:30Z",
                          "2019-02-29T00:00:00Z", "2019-12-32T00:00:00Z", "2019-12-09T24:00:00Z",
                          "2019-12-09T16:60:00Z", "2019-12-09T16:34:30+01:00",
                          "2019-12-09T16:34:30.Z", "2019-12-09T16:34:30Zjunk", "yesterday"})
    EXPECT_FALSE(parse_utc(bad, ms)) << bad;

  char buf[32];
  ASSERT_GT(format_utc_seconds(1'575'909'270'000, buf, sizeof buf), 0u);
  EXPECT_STREQ(buf, "2019-12-09T16:34:30Z");
  ASSERT_GT(format_utc_seconds(1'575'909'270'600, buf, sizeof buf), 0u);  // rounds
  EXPECT_STREQ(buf, "2019-12-09T16:34:31Z");
  ASSERT_GT(format_utc_seconds(-1, buf, sizeof buf), 0u);
  EXPECT_STREQ(buf, "1970-01-01T00:00:00Z");
  EXPECT_EQ(format_utc_seconds(0, buf, 10), 0u);  // does not fit
}

TEST(TrackingTimeTest, TleEpochs) {
  // 19343.69339541: 2019, day 343 (December 9th) at 16:38:29.363 UTC.
  EXPECT_NEAR(tle_epoch_unix_ms(2019, 343.69339541), 1'575'909'509'363.4, 0.5);
  // Days since 1949-12-31 00:00, as SGP4 counts: 2000-01-01 00:00 is day 18263.
  EXPECT_DOUBLE_EQ(tle_epoch_days_1950(2000, 1.0), 18263.0);
  EXPECT_NEAR(tle_epoch_days_1950(2019, 343.69339541),
              18263.0 +
                  static_cast<double>(days_from_civil(2019, 12, 9) - days_from_civil(2000, 1, 1)) +
                  0.69339541,
              1e-8);
  EXPECT_EQ(days_from_civil(1970, 1, 1), 0);
  EXPECT_EQ(days_from_civil(2000, 3, 1), 11'017);
}

}  // namespace
}  // namespace rotord::tracking
