// The matcher behind recognising a client's pass (rotator/goto_match.hpp):
// the flip frame undone, the tolerance against the object's recent path, a
// recognition only after kMinHits go-tos near one object, or two whose step
// is the object's own motion, once every candidate was compared (never at
// one go-to), a bounded sweep, and no recognition when two objects match.
#include "rotator/goto_match.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "iss_elements.hpp"
#include "tracking/julian.hpp"

namespace rotord {
namespace {

using testing::kIssLine1;
using testing::kIssLine2;

class GotoMatchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    tracking::Geodetic boulder;
    boulder.lat_deg = 40.015;
    boulder.lon_deg = -105.27;
    boulder.alt_m = 1655.0;
    station_ = tracking::Observer(boulder);
    // The ISS's pass through north over Boulder, near its culmination.
    ASSERT_TRUE(tracking::parse_utc("2019-12-09T22:40:30Z", t0_));
    // Near its culmination (13.9 deg), where it moves a threshold in 20 s.
    ASSERT_TRUE(tracking::parse_utc("2019-12-09T22:49:00Z", t1_));
    const std::string iss = testing::iss_tle_text();
    ASSERT_TRUE(catalog_.put(iss, 0).ok());
    tracking::Tle tle;
    ASSERT_TRUE(tracking::parse_tle(kIssLine1, kIssLine2, tle).ok());
    ASSERT_EQ(iss_.set_satellite(tle), tracking::Sgp4Error::kOk);
  }
  tracking::LookAngles iss_at(std::int64_t t) {
    tracking::LookAngles look;
    EXPECT_EQ(iss_.look(t, station_, look), tracking::Sgp4Error::kOk);
    return look;
  }
  /// A go-to at the ISS's position of `t_ms` (offset by `daz` in azimuth,
  /// `del` in elevation) received at `t_ms + lag_ms`.
  GotoMatcher::Verdict goto_iss(GotoMatcher& m, std::int64_t t_ms, int budget, float daz = 0.0f,
                                std::int64_t lag_ms = 0, float del = 0.0f) {
    const tracking::LookAngles l = iss_at(t_ms);
    float az = static_cast<float>(l.az_deg) + daz;
    float el = static_cast<float>(l.el_deg) + del;
    GotoMatcher::sky_direction(az, el);
    return m.consider(az, el, t_ms + lag_ms, station_, &catalog_, budget);
  }

  tracking::Observer station_;
  tracking::TleCatalog catalog_;
  tracking::SkyTarget iss_;
  std::int64_t t0_ = 0;
  std::int64_t t1_ = 0;
  /// A threshold client's step near the culmination.
  static constexpr std::int64_t kStepMs = 20000;
};

TEST(GotoMatch, TheFlipFrameIsTheSameDirection) {
  float az = 300.0f, el = 120.0f;  // Gpredict with max el 180: az + 180, 180 - el
  GotoMatcher::sky_direction(az, el);
  EXPECT_NEAR(az, 120.0f, 1e-3f);
  EXPECT_NEAR(el, 60.0f, 1e-3f);
  az = -20.0f, el = 30.0f;
  GotoMatcher::sky_direction(az, el);
  EXPECT_NEAR(az, 340.0f, 1e-3f);
  EXPECT_NEAR(el, 30.0f, 1e-3f);
}

TEST_F(GotoMatchTest, NearTheObjectOrWhereItWasRecentlyButNotElsewhere) {
  const tracking::LookAngles now = iss_at(t0_);
  const auto near = [&](const tracking::LookAngles& l, float daz, float del) {
    return GotoMatcher::near(iss_, static_cast<float>(l.az_deg) + daz,
                             static_cast<float>(l.el_deg) + del, t0_, station_);
  };
  EXPECT_TRUE(near(now, 0.0f, 0.0f));
  EXPECT_TRUE(near(now, 0.0f, 2.0f));
  // A client that sent where the ISS was a few seconds ago (its threshold).
  EXPECT_TRUE(near(iss_at(t0_ - 4000), 0.0f, 0.0f));
  // Two minutes stale, or 5 deg across its path: not the ISS.
  EXPECT_FALSE(near(iss_at(t0_ - 120000), 0.0f, 0.0f));
  EXPECT_FALSE(near(now, 0.0f, 5.0f));
  EXPECT_FALSE(near(now, 0.0f, -5.0f));
  // The Sun is not where the ISS is.
  tracking::SkyTarget sun;
  sun.set_body(tracking::Body::kSun);
  EXPECT_FALSE(GotoMatcher::near(sun, static_cast<float>(now.az_deg),
                                 static_cast<float>(now.el_deg), t0_, station_));
}

TEST_F(GotoMatchTest, RecognisedAfterThreeGotosInStepWithOneObject) {
  // Go-tos 5 s apart: the ISS moves too little between two for their step
  // to say anything (under kInStepMinDeg), so three are needed.
  GotoMatcher m;
  const int all = GotoMatcher::kMaxCandidates;
  GotoMatcher::Verdict v = goto_iss(m, t0_, all);
  EXPECT_FALSE(v.recognised);
  EXPECT_EQ(v.evaluated, 3);  // the ISS, the Sun, the Moon
  v = goto_iss(m, t0_ + 5000, all);
  EXPECT_FALSE(v.recognised);
  EXPECT_EQ(v.evaluated, 1);                      // only the candidate still in
  v = goto_iss(m, t0_ + 10000, all, 0.0f, 3000);  // a client 3 s late
  EXPECT_TRUE(v.recognised);
  EXPECT_EQ(v.candidate, 0);
  EXPECT_FALSE(v.ambiguous);
}

/// The angle between two sky directions (deg).
double separation_deg(const tracking::LookAngles& a, const tracking::LookAngles& b) {
  const double r = 3.14159265358979323846 / 180.0;
  const double c =
      std::sin(a.el_deg * r) * std::sin(b.el_deg * r) +
      std::cos(a.el_deg * r) * std::cos(b.el_deg * r) * std::cos((a.az_deg - b.az_deg) * r);
  return std::acos(std::fmin(1.0, c)) / r;
}

TEST_F(GotoMatchTest, TwoGotosWhoseStepIsTheObjectsMotionAreRecognised) {
  // A threshold client (Gpredict 5 deg) sends when the ISS has moved its
  // threshold: two go-tos on the ISS's path, a step apart that is the
  // ISS's own motion over the time between them. A single go-to is never
  // recognised; the second is, with a lag that differs by a second between
  // them or a clock 3 s late for both.
  const double moved = separation_deg(iss_at(t1_), iss_at(t1_ + kStepMs));
  std::printf("[ goto_match ] the ISS moves %.1f deg in 20 s\n", moved);
  ASSERT_GT(moved, GotoMatcher::kInStepMinDeg);
  ASSERT_LT(moved, GotoMatcher::kLookBackMaxDeg);
  const int all = GotoMatcher::kMaxCandidates;
  for (const std::int64_t lag_ms : {0, 3000}) {
    GotoMatcher m;
    EXPECT_FALSE(goto_iss(m, t1_, all, 0.0f, lag_ms).recognised) << "a single go-to";
    const GotoMatcher::Verdict v = goto_iss(m, t1_ + kStepMs, all, 0.0f, lag_ms + 1000);
    EXPECT_TRUE(v.recognised) << "lag " << lag_ms;
    EXPECT_EQ(v.candidate, 0);
  }
}

TEST_F(GotoMatchTest, TwoGotosNearTheObjectButNotInStepWaitForAThird) {
  const int all = GotoMatcher::kMaxCandidates;
  {
    // Both within the tolerance of the ISS's path, but 1.5 deg above it
    // and then 1.5 deg below: the step is not the ISS's motion.
    GotoMatcher m;
    goto_iss(m, t1_, all, 0.0f, 0, 1.5f);
    EXPECT_FALSE(goto_iss(m, t1_ + kStepMs, all, 0.0f, 0, -1.5f).recognised);
    EXPECT_TRUE(goto_iss(m, t1_ + kStepMs + 5000, all).recognised) << "the third hit";
  }
  {
    // The same point twice, a step apart: still near where the ISS was, but it
    // moved and the stream did not.
    GotoMatcher m;
    goto_iss(m, t1_, all);
    EXPECT_FALSE(goto_iss(m, t1_, all, 0.0f, kStepMs).recognised);
  }
  {
    // A step the wrong way: on the ISS's path, then back along it where
    // the ISS was 10 s before, 10 s later (still within its recent path).
    GotoMatcher m;
    goto_iss(m, t1_ + kStepMs, all);
    EXPECT_FALSE(goto_iss(m, t1_ + kStepMs - 10000, all, 0.0f, 20000).recognised);
  }
}

TEST_F(GotoMatchTest, ASmallBudgetSpreadsTheSweepOverGotos) {
  GotoMatcher m;
  int recognised_at = 0;
  for (int n = 1; n <= 8 && recognised_at == 0; ++n) {
    const GotoMatcher::Verdict v = goto_iss(m, t0_ + 4000 * n, 1);
    EXPECT_LE(v.evaluated, 1);
    if (v.recognised) recognised_at = n;
  }
  // Three go-tos to compare the three candidates once, then two more hits.
  EXPECT_EQ(recognised_at, 5);
}

TEST_F(GotoMatchTest, AMissIsOutAndTwoObjectsOnOneOrbitAreAmbiguous) {
  GotoMatcher m;
  const int all = GotoMatcher::kMaxCandidates;
  goto_iss(m, t0_, all);
  goto_iss(m, t0_ + 5000, all);
  // A go-to 20 deg off the ISS: nothing is left in; the comparison starts
  // over with the next go-to, which needs three hits again.
  EXPECT_FALSE(goto_iss(m, t0_ + 10000, all, 20.0f).recognised);
  EXPECT_FALSE(goto_iss(m, t0_ + 15000, all).recognised);
  EXPECT_FALSE(goto_iss(m, t0_ + 20000, all).recognised);
  EXPECT_TRUE(goto_iss(m, t0_ + 25000, all).recognised);

  const std::string twin = testing::twin_tle_text();
  ASSERT_TRUE(catalog_.put(twin, 0).ok());
  GotoMatcher::Verdict v;
  for (int n = 0; n < 10; ++n) {
    v = goto_iss(m, t0_ + 30000 + 4000 * n, all);
    EXPECT_FALSE(v.recognised);
  }
  EXPECT_TRUE(v.ambiguous);
  // Nor when their steps are the motion of both.
  m.restart();
  for (int n = 0; n < 4; ++n) {
    v = goto_iss(m, t0_ + 30000 * n, all);
    EXPECT_FALSE(v.recognised);
  }
  EXPECT_TRUE(v.ambiguous);
}

}  // namespace
}  // namespace rotord
