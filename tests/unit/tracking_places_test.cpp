// Maidenhead locators and great-circle bearings against
// tests/data/tracking/places.csv (make_reference.py: vector algebra on the
// same sphere, an independent formula) and a few values known by hand.
#include <gtest/gtest.h>

#include <string_view>

#include "csv_rows.hpp"
#include "tracking/places.hpp"

extern const char* const kPlacesCsv[];
extern const unsigned long kPlacesCsv_count;

namespace rotord::tracking {
namespace {

using test::bearing_difference_deg;
using test::csv_fields;
using test::csv_number;

TEST(TrackingPlacesTest, LocatorCentresAndBearingsMatchTheReference) {
  int rows = 0;
  for (unsigned long line = 1; line < kPlacesCsv_count; ++line) {
    std::string_view f[7];
    ASSERT_EQ(csv_fields(kPlacesCsv[line], f, 7), 7u);
    LatLon target;
    ASSERT_TRUE(maidenhead_centre(f[2], target)) << f[2];
    EXPECT_NEAR(target.lat_deg, csv_number(f[3]), 1e-9) << f[2];
    EXPECT_NEAR(target.lon_deg, csv_number(f[4]), 1e-9) << f[2];
    const LatLon station{csv_number(f[0]), csv_number(f[1])};
    const Bearing shortp = great_circle(station, target);
    EXPECT_LT(bearing_difference_deg(shortp.azimuth_deg, csv_number(f[5])), 1e-5) << f[2];
    EXPECT_NEAR(shortp.distance_km, csv_number(f[6]), 1e-3) << f[2];
    const Bearing longp = great_circle(station, target, Path::kLong);
    EXPECT_LT(bearing_difference_deg(longp.azimuth_deg, csv_number(f[5]) + 180.0), 1e-5);
    EXPECT_NEAR(longp.distance_km + shortp.distance_km, 40030.2289, 0.001);
    ++rows;
  }
  EXPECT_EQ(rows, 48);
}

TEST(TrackingPlacesTest, KnownLocators) {
  LatLon p;
  ASSERT_TRUE(maidenhead_centre("JN58td", p));  // Munich area
  EXPECT_NEAR(p.lat_deg, 48.1458, 1e-4);
  EXPECT_NEAR(p.lon_deg, 11.625, 1e-4);
  ASSERT_TRUE(maidenhead_centre("jn58TD", p));  // either case
  EXPECT_NEAR(p.lat_deg, 48.1458, 1e-4);
  ASSERT_TRUE(maidenhead_centre("AA00", p));
  EXPECT_NEAR(p.lat_deg, -89.5, 1e-9);
  EXPECT_NEAR(p.lon_deg, -179.0, 1e-9);
  ASSERT_TRUE(maidenhead_centre("RR99xx99xx", p));
  EXPECT_LT(p.lat_deg, 90.0);
  EXPECT_GT(p.lat_deg, 89.9999);
}

TEST(TrackingPlacesTest, RefusesMalformedLocators) {
  LatLon p;
  for (const char* bad : {"", "JN", "JN5", "JN58t", "SN58", "JS58", "JNA8", "JN58yy", "JN58td5",
                          "JN58td5a", "JN58tdaa", "JN58td55zz", "JN58td55aa00", "JN 58"})
    EXPECT_FALSE(maidenhead_centre(bad, p)) << bad;
}

TEST(TrackingPlacesTest, DueEastAlongTheEquatorAndTheLongWayRound) {
  const Bearing b = great_circle({0, 0}, {0, 90});
  EXPECT_NEAR(b.azimuth_deg, 90.0, 1e-9);
  EXPECT_NEAR(b.distance_km, 10007.5572, 1e-3);
  const Bearing l = great_circle({0, 0}, {0, 90}, Path::kLong);
  EXPECT_NEAR(l.azimuth_deg, 270.0, 1e-9);
  EXPECT_NEAR(l.distance_km, 30022.6717, 1e-3);
  // The same place: no distance.
  EXPECT_NEAR(great_circle({52, 5}, {52, 5}).distance_km, 0.0, 1e-9);
}

}  // namespace
}  // namespace rotord::tracking
