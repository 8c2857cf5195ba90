#include "tracking/tle.hpp"

#include <gtest/gtest.h>

#include <string>

#include "iss_elements.hpp"

namespace rotord::tracking {
namespace {

constexpr const char* kIss1 = testing::kIssLine1;
constexpr const char* kIss2 = testing::kIssLine2;

TEST(TleTest, ParsesEveryFieldOfAValidElementSet) {
  Tle t;
  const TleResult r = parse_tle(kIss1, kIss2, t);
  ASSERT_TRUE(r.ok()) << tle_error_name(r.error) << " " << r.field;
  EXPECT_EQ(t.catalog, 25544u);
  EXPECT_EQ(t.classification, 'U');
  EXPECT_STREQ(t.designator, "98067A");
  EXPECT_EQ(t.epoch_year, 2019);
  EXPECT_DOUBLE_EQ(t.epoch_day, 343.69339541);
  EXPECT_DOUBLE_EQ(t.ndot, 0.00001764);
  EXPECT_DOUBLE_EQ(t.nddot, 0.0);
  EXPECT_DOUBLE_EQ(t.bstar, 0.38792e-4);
  EXPECT_DOUBLE_EQ(t.inclination_deg, 51.6439);
  EXPECT_DOUBLE_EQ(t.raan_deg, 211.2001);
  EXPECT_DOUBLE_EQ(t.eccentricity, 0.0007417);
  EXPECT_DOUBLE_EQ(t.arg_perigee_deg, 17.6667);
  EXPECT_DOUBLE_EQ(t.mean_anomaly_deg, 85.6398);
  EXPECT_DOUBLE_EQ(t.mean_motion_rev_day, 15.50103472);
  EXPECT_EQ(t.revolution, 20248u);
  EXPECT_EQ(t.element_set, 999u);
}

TEST(TleTest, ToleratesCrLfAndTrailingBlanks) {
  Tle t;
  EXPECT_TRUE(parse_tle(std::string(kIss1) + "\r\n", std::string(kIss2) + "  \r", t).ok());
}

TEST(TleTest, RefusesAWrongChecksumAndSaysWhichLine) {
  std::string bad = kIss2;
  bad[68] = '3';
  Tle t;
  const TleResult r = parse_tle(kIss1, bad, t);
  EXPECT_EQ(r.error, TleError::kChecksum);
  EXPECT_STREQ(r.field, "line 2");
  // A changed digit is caught too (the sum changes).
  std::string changed = kIss1;
  changed[20] = '8';
  EXPECT_EQ(parse_tle(changed, kIss2, t).error, TleError::kChecksum);
  EXPECT_EQ(tle_checksum(kIss1), 1);
}

TEST(TleTest, RefusesTheVerificationSetsDeliberatelyWrongChecksums) {
  Tle t;
  EXPECT_EQ(parse_tle("1 33333U 05037B   05333.02012661  .25992681  00000-0  24476-3 0  1534",
                      "2 33333  96.4736 157.9986 9950000 244.0492 110.6523  4.00004038 10708", t)
                .error,
            TleError::kChecksum);
}

TEST(TleTest, RefusesFormatErrorsWithTheirField) {
  Tle t;
  EXPECT_EQ(parse_tle(std::string(kIss1).substr(0, 60), kIss2, t).error, TleError::kLineLength);
  EXPECT_EQ(parse_tle(kIss2, kIss1, t).error, TleError::kLineNumber);
  EXPECT_EQ(parse_tle(std::string(kIss1) + " extra", kIss2, t).error, TleError::kLineLength);
  // Letters in the inclination (checksum not checked here to reach the field).
  std::string bad = kIss2;
  bad[9] = 'x';
  TleResult r = parse_tle(kIss1, bad, t, {.verify_checksum = false});
  EXPECT_EQ(r.error, TleError::kField);
  EXPECT_STREQ(r.field, "inclination");
  bad = kIss2;
  bad[28] = '.';
  r = parse_tle(kIss1, bad, t, {.verify_checksum = false});
  EXPECT_EQ(r.error, TleError::kField);
  EXPECT_STREQ(r.field, "eccentricity");
  // Lines of two objects.
  std::string other = kIss2;
  other[6] = '5';
  EXPECT_EQ(parse_tle(kIss1, other, t, {.verify_checksum = false}).error,
            TleError::kCatalogMismatch);
}

TEST(TleTest, DecodesAlpha5CatalogNumbers) {
  std::uint32_t n = 0;
  ASSERT_TRUE(parse_catalog_number("A0001", n));
  EXPECT_EQ(n, 100001u);
  ASSERT_TRUE(parse_catalog_number("H9999", n));
  EXPECT_EQ(n, 179999u);
  ASSERT_TRUE(parse_catalog_number("J0000", n));  // I is skipped
  EXPECT_EQ(n, 180000u);
  ASSERT_TRUE(parse_catalog_number("P0000", n));  // O is skipped
  EXPECT_EQ(n, 230000u);
  ASSERT_TRUE(parse_catalog_number("Z9999", n));
  EXPECT_EQ(n, 339999u);
  ASSERT_TRUE(parse_catalog_number("    5", n));
  EXPECT_EQ(n, 5u);
  EXPECT_FALSE(parse_catalog_number("I0001", n));
  EXPECT_FALSE(parse_catalog_number("O0001", n));
  EXPECT_FALSE(parse_catalog_number("A00x1", n));

  // A whole TLE with an Alpha-5 number, checksums recomputed ('-' counts 1, letters 0).
  std::string l1 = "1 B1234U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  999";
  std::string l2 = "2 B1234  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482";
  l1 += static_cast<char>('0' + tle_checksum(l1));
  l2[68] = static_cast<char>('0' + tle_checksum(l2));
  Tle t;
  ASSERT_TRUE(parse_tle(l1, l2, t).ok());
  EXPECT_EQ(t.catalog, 111234u);
}

TEST(TleTest, FindsANamedSetInAThreeLineFile) {
  const std::string text = std::string("ISS (ZARYA)\r\n") + kIss1 + "\r\n" + kIss2 + "\r\n" +
                           "0 OTHER\n" + kIss1 + "\n" + kIss2 + "\n";
  Tle t;
  ASSERT_TRUE(find_tle(text, "iss (zarya)", t).ok());
  EXPECT_STREQ(t.name, "ISS (ZARYA)");
  ASSERT_TRUE(find_tle(text, "OTHER", t).ok());
  EXPECT_STREQ(t.name, "OTHER");
  ASSERT_TRUE(find_tle(text, "", t).ok());
  EXPECT_STREQ(t.name, "ISS (ZARYA)");
  EXPECT_EQ(find_tle(text, "HUBBLE", t).error, TleError::kNoElements);
  EXPECT_EQ(find_tle("no elements here\n", "", t).error, TleError::kNoElements);
  // A bare two-line set has no name.
  ASSERT_TRUE(find_tle(std::string(kIss1) + "\n" + kIss2, "", t).ok());
  EXPECT_STREQ(t.name, "");
}

}  // namespace
}  // namespace rotord::tracking
