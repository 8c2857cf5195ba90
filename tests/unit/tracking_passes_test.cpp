// The pass finder against tests/data/tracking/passes.csv (skyfield's
// find_events for the ISS, PyEphem's rising/transit/setting for the Sun and
// the Moon) and keyhole_iss.csv (near-overhead ISS passes with their maximum
// rates computed with python-sgp4 for observers under the ISS's track; see
// tests/data/tracking/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string_view>

#include "csv_rows.hpp"
#include "iss_elements.hpp"
#include "tracking/julian.hpp"
#include "tracking/pass_finder.hpp"

extern const char* const kPassesCsv[];
extern const unsigned long kPassesCsv_count;
extern const char* const kKeyholeIssCsv[];
extern const unsigned long kKeyholeIssCsv_count;

namespace rotord::tracking {
namespace {

using test::csv_fields;
using test::csv_number;

constexpr const char* kIss1 = testing::kIssLine1;
constexpr const char* kIss2 = testing::kIssLine2;

constexpr int kMaxPasses = 24;

struct Found {
  Pass passes[kMaxPasses];
  int count = 0;
  PassFinder::Status last = PassFinder::Status::kSearching;
  int calls = 0;
};

Found find_all(SkyTarget& target, const Observer& observer, std::int64_t from, std::int64_t to,
               double min_el, int budget) {
  Found f;
  PassFinder finder;
  finder.start(target, observer, from, to, min_el);
  for (;;) {
    f.last = finder.step(budget);
    ++f.calls;
    if (f.last == PassFinder::Status::kFound && f.count < kMaxPasses)
      f.passes[f.count++] = finder.pass();
    if (f.last == PassFinder::Status::kDone || f.last == PassFinder::Status::kError) break;
    if (f.calls > 1'000'000) break;
  }
  return f;
}

constexpr const char* kMolniya1 =
    "1 08195U 75081A   06176.33215444  .00000099  00000-0  11873-3 0   813";
constexpr const char* kMolniya2 =
    "2 08195  64.1586 279.0717 6877146 264.7651  20.2257  2.00491383225656";

SkyTarget from_tle(const char* line1, const char* line2) {
  Tle tle;
  EXPECT_TRUE(parse_tle(line1, line2, tle).ok());
  SkyTarget t;
  EXPECT_EQ(t.set_satellite(tle), Sgp4Error::kOk);
  return t;
}

SkyTarget iss() {
  return from_tle(kIss1, kIss2);
}

std::int64_t utc(std::string_view text) {
  std::int64_t ms = 0;
  EXPECT_TRUE(parse_utc(text, ms)) << text;
  return ms;
}

// Each row is a day's search; under qemu's soft float that is seconds of
// emulation per row, so the Cortex-M0+ run checks every fourth (the host all).
#if defined(__arm__)
constexpr unsigned long kPassRowStride = 4;
#else
constexpr unsigned long kPassRowStride = 1;
#endif

TEST(TrackingPassesTest, PassesMatchSkyfieldAndPyEphem) {
  double worst_edge_s[2] = {0, 0}, worst_max_el[2] = {0, 0};
  int compared = 0;
  for (unsigned long line = 1; line < kPassesCsv_count; line += kPassRowStride) {
    std::string_view f[11];
    ASSERT_EQ(csv_fields(kPassesCsv[line], f, 11), 11u);
    SkyTarget target;
    const bool leo = f[0] == "ISS";
    const bool satellite = leo || f[0] == "MOLNIYA";
    if (leo) {
      target = iss();
    } else if (satellite) {
      target = from_tle(kMolniya1, kMolniya2);
    } else {
      target.set_body(f[0] == "sun" ? Body::kSun : Body::kMoon);
    }
    const Observer observer(Geodetic{csv_number(f[1]), csv_number(f[2]), csv_number(f[3])});
    const Found found = find_all(target, observer, utc(f[5]), utc(f[6]), csv_number(f[4]), 50);
    ASSERT_EQ(found.last, PassFinder::Status::kDone);
    const std::int64_t aos = utc(f[7]);
    const Pass* match = nullptr;
    for (int i = 0; i < found.count; ++i)
      if (std::llabs(found.passes[i].aos_ms - aos) < 60'000) match = &found.passes[i];
    ASSERT_NE(match, nullptr) << kPassesCsv[line];
    // Slower risers (Molniya near apogee, Sun, Moon) turn the same elevation
    // difference into more seconds.
    const double edge_tolerance_s = leo ? 1.0 : 5.0;
    const double aos_s = static_cast<double>(match->aos_ms - aos) / 1000.0;
    const double los_s = static_cast<double>(match->los_ms - utc(f[8])) / 1000.0;
    EXPECT_LT(std::fabs(aos_s), edge_tolerance_s) << kPassesCsv[line];
    EXPECT_LT(std::fabs(los_s), edge_tolerance_s) << kPassesCsv[line];
    const double max_el_error = std::fabs(match->max_el_deg - csv_number(f[10]));
    EXPECT_LT(max_el_error, satellite ? 0.03 : 0.05) << kPassesCsv[line];
    // The Moon culminates up to minutes from its transit (its declination moves).
    const double max_s = static_cast<double>(match->max_el_ms - utc(f[9])) / 1000.0;
    EXPECT_LT(std::fabs(max_s), leo ? 2.0 : (satellite ? 120.0 : 600.0)) << kPassesCsv[line];
    EXPECT_FALSE(match->aos_clipped);
    EXPECT_FALSE(match->los_clipped);
    const int k = leo ? 0 : 1;
    worst_edge_s[k] = std::fmax(worst_edge_s[k], std::fmax(std::fabs(aos_s), std::fabs(los_s)));
    worst_max_el[k] = std::fmax(worst_max_el[k], max_el_error);
    ++compared;
  }
  std::printf(
      "%d passes: ISS AOS/LOS within %.2f s, max el %.4f deg; Molniya/Sun/Moon %.2f s, %.4f deg\n",
      compared, worst_edge_s[0], worst_max_el[0], worst_edge_s[1], worst_max_el[1]);
  EXPECT_EQ(compared, static_cast<int>((kPassesCsv_count - 2) / kPassRowStride + 1));
  EXPECT_GE(compared, 12);
}

TEST(TrackingPassesTest, FindsEveryCompletePassAndNoOther) {
  // Boulder, one day, ISS above 0 deg: the reference lists the complete passes.
  SkyTarget target = iss();
  const Observer observer(Geodetic{40.015, -105.27, 1655.0});
  const Found found =
      find_all(target, observer, utc("2019-12-09T12:00:00Z"), utc("2019-12-10T12:00:00Z"), 0.0, 50);
  int reference = 0;
  for (unsigned long line = 1; line < kPassesCsv_count; ++line) {
    std::string_view f[11];
    csv_fields(kPassesCsv[line], f, 11);
    if (f[0] == "ISS" && f[1] == "40.0150" && f[4] == "0.0") ++reference;
  }
  int complete = 0;
  for (int i = 0; i < found.count; ++i)
    if (!found.passes[i].aos_clipped && !found.passes[i].los_clipped) ++complete;
  EXPECT_EQ(complete, reference);
  EXPECT_GE(reference, 4);
}

TEST(TrackingPassesTest, TheSameResultWhateverTheWorkPerCall) {
  SkyTarget a = iss(), b = iss();
  const Observer observer(Geodetic{51.5074, -0.1278, 20.0});
  const std::int64_t from = utc("2019-12-09T12:00:00Z"), to = utc("2019-12-10T00:00:00Z");
  const Found one = find_all(a, observer, from, to, 5.0, 1);
  const Found many = find_all(b, observer, from, to, 5.0, 1000);
  ASSERT_EQ(one.count, many.count);
  ASSERT_GT(one.count, 0);
  for (int i = 0; i < one.count; ++i) {
    EXPECT_EQ(one.passes[i].aos_ms, many.passes[i].aos_ms);
    EXPECT_EQ(one.passes[i].los_ms, many.passes[i].los_ms);
    EXPECT_EQ(one.passes[i].max_el_ms, many.passes[i].max_el_ms);
  }
  EXPECT_GT(one.calls, 20 * many.calls);  // it really was spread out
}

TEST(TrackingPassesTest, APassInProgressAtEitherEndIsClipped) {
  // The Sun at Greenwich around noon of the equinox: up for the whole window.
  SkyTarget sun;
  sun.set_body(Body::kSun);
  const Observer observer(Geodetic{51.4769, 0.0, 0.0});
  const Found found =
      find_all(sun, observer, utc("2024-03-20T11:00:00Z"), utc("2024-03-20T13:00:00Z"), 0.0, 50);
  ASSERT_EQ(found.count, 1);
  const Pass& p = found.passes[0];
  EXPECT_TRUE(p.aos_clipped);
  EXPECT_TRUE(p.los_clipped);
  EXPECT_EQ(p.aos_ms, utc("2024-03-20T11:00:00Z"));
  EXPECT_EQ(p.los_ms, utc("2024-03-20T13:00:00Z"));
  // Culmination near 12:07 UTC (equation of time), about 38.6 deg up.
  EXPECT_NEAR(static_cast<double>(p.max_el_ms - utc("2024-03-20T12:07:30Z")) / 1000.0, 0.0, 90.0);
  EXPECT_NEAR(p.max_el_deg, 38.6, 0.3);
}

TEST(TrackingPassesTest, ADecayedSatelliteIsAnError) {
  // MINOTAUR R/B from the verification set: decays within 60 minutes of epoch.
  Tle tle;
  ASSERT_TRUE(parse_tle("1 28872U 05037B   05333.02012661  .25992681  00000-0  24476-3 0  1534",
                        "2 28872  96.4736 157.9986 0303955 244.0492 110.6523 16.46015938 10708",
                        tle)
                  .ok());
  SkyTarget target;
  ASSERT_EQ(target.set_satellite(tle), Sgp4Error::kOk);
  const std::int64_t epoch = static_cast<std::int64_t>(tle_epoch_unix_ms(2005, 333.02012661));
  PassFinder finder;
  finder.start(target, Observer{}, epoch, epoch + 3 * 3'600'000, 0.0);
  PassFinder::Status s = PassFinder::Status::kSearching;
  for (int i = 0; i < 10'000 && s != PassFinder::Status::kError && s != PassFinder::Status::kDone;
       ++i)
    s = finder.step(10);
  EXPECT_EQ(s, PassFinder::Status::kError);
  EXPECT_EQ(finder.error(), Sgp4Error::kDecayed);
}

TEST(TrackingPassesTest, NearOverheadIssPassesAndTheirRates) {
  // Observers under the ISS's track at 19:31:38 UTC (keyhole_iss.csv's check).
  for (unsigned long line = 1; line < kKeyholeIssCsv_count; ++line) {
    std::string_view f[8];
    ASSERT_EQ(csv_fields(kKeyholeIssCsv[line], f, 8), 8u);
    SkyTarget target = iss();
    const Observer observer(Geodetic{csv_number(f[1]), csv_number(f[2]), 0.0});
    const std::int64_t tca = utc(f[3]);
    const Found found = find_all(target, observer, tca - 15 * 60'000, tca + 15 * 60'000, 0.0, 50);
    ASSERT_EQ(found.count, 1) << kKeyholeIssCsv[line];
    const Pass& p = found.passes[0];
    const double max_el = csv_number(f[4]);
    EXPECT_NEAR(p.max_el_deg, max_el, 0.02) << kKeyholeIssCsv[line];
    EXPECT_NEAR(static_cast<double>(p.max_el_ms - tca) / 1000.0, 0.0, 1.0);
    EXPECT_NEAR(p.max_el_rate_deg_s, csv_number(f[7]), 0.005 * csv_number(f[7]));
    // The azimuth rate peaks sharply at culmination: within 2 % up to 85 deg;
    // above, the 0.1 s culmination search only samples the spike (and the
    // reference itself was sampled).
    const double az_rate = csv_number(f[6]);
    if (max_el <= 85.0) {
      EXPECT_NEAR(p.max_az_rate_deg_s, az_rate, 0.02 * az_rate) << kKeyholeIssCsv[line];
    } else {
      EXPECT_GT(p.max_az_rate_deg_s, 0.3 * az_rate) << kKeyholeIssCsv[line];
    }
    std::printf("max el %.3f (ref %.3f), az rate %.2f (ref %.2f), el rate %.4f (ref %.4f) deg/s\n",
                p.max_el_deg, max_el, p.max_az_rate_deg_s, az_rate, p.max_el_rate_deg_s,
                csv_number(f[7]));
  }
}

}  // namespace
}  // namespace rotord::tracking
