// The whole-pass plan: wrap through the overlap, flip, and the fallback
// when a pass cannot fit, on synthetic passes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "tracking/track_plan.hpp"

namespace rotord::tracking {
namespace {

/// A pass from az0 to az1 (linearly, through north when asked) with the
/// elevation rising to max_el and back, sampled over 600 s.
std::unique_ptr<PassTable> pass(float az0, float az1, float max_el) {
  auto t = std::make_unique<PassTable>();
  t->begin(0, 600000);
  while (!t->complete()) {
    const float f = static_cast<float>(t->next_time()) / 600000.0f;
    LookAngles look;
    float az = az0 + (az1 - az0) * f;
    while (az >= 360.0f) az -= 360.0f;
    while (az < 0.0f) az += 360.0f;
    look.az_deg = az;
    look.el_deg = max_el * (1.0f - (2.0f * f - 1.0f) * (2.0f * f - 1.0f));
    look.az_rate_deg_s = az1 > az0 ? 1.0 : -1.0;
    t->add(look);
  }
  return t;
}

Travel g5500(float el_max = 180.0f) {
  return Travel{0.0f, 450.0f, false, true, 0.0f, el_max};
}

TEST(PassPlan, UnwrapsThroughNorthAndUsesTheOverlap) {
  auto t = pass(312.0f, 434.0f, 14.0f);
  EXPECT_NEAR(t->az_lowest_deg(), 312.0f, 0.01f);
  EXPECT_NEAR(t->az_highest_deg(), 434.0f, 0.2f);
  const PassPlan p = choose_plan(*t, g5500(90.0f), 30.0f, 0.0f, 2.0f);
  EXPECT_TRUE(p.fits);
  EXPECT_FALSE(p.flip);
  EXPECT_FLOAT_EQ(p.az_offset_deg, 0.0f);
  float az = 0, el = 0;
  plan_position(*t, p, 600000, az, el);
  EXPECT_NEAR(az, 434.0f, 0.2f);
}

TEST(PassPlan, FlipsWhenThatTurnsLeastOrWhenNothingElseFits) {
  // 200 -> 460 spans 260 deg through north: no turn of 0..450 holds it
  // unflipped with the margin; flipped it is 20..280.
  auto wide = pass(200.0f, 460.0f, 60.0f);
  const PassPlan p = choose_plan(*wide, g5500(), 200.0f, 0.0f, 2.0f);
  EXPECT_TRUE(p.fits);
  EXPECT_TRUE(p.flip);
  float az = 0, el = 0;
  plan_position(*wide, p, 0, az, el);
  EXPECT_NEAR(az, 20.0f, 0.01f);
  EXPECT_NEAR(el, 180.0f, 0.01f);
  // Without flip (el 0..90) it cannot fit: the fallback says so and starts
  // inside the travel.
  const PassPlan q = choose_plan(*wide, g5500(90.0f), 200.0f, 0.0f, 2.0f);
  EXPECT_FALSE(q.fits);
  EXPECT_FALSE(q.flip);
}

TEST(PassPlan, ChoosesTheTurnNearestWhereTheAntennaIs) {
  auto t = pass(200.0f, 300.0f, 40.0f);
  const Travel spid{-180.0f, 540.0f, false, true, 0.0f, 180.0f};
  const PassPlan p = choose_plan(*t, spid, -100.0f, 10.0f, 2.0f);
  EXPECT_TRUE(p.fits);
  EXPECT_FALSE(p.flip);
  EXPECT_FLOAT_EQ(p.az_offset_deg, -360.0f);  // -160 .. -60
  const PassPlan q = choose_plan(*t, spid, 250.0f, 10.0f, 2.0f);
  EXPECT_FLOAT_EQ(q.az_offset_deg, 0.0f);
}

TEST(PassPlan, APassNoTurnHoldsUnwindsOnceWhereTheElevationIsLowest) {
  // 300 -> 600 (300 deg through north) on a G-5500 without flip: no turn
  // of 0..450 holds it, and holding at the end stop would lose half the
  // pass. The elevation peaks late (at 3/4 of the pass); the pass leaves
  // the travel at 0.49 (448), so the plan unwinds as early as the second
  // turn holds the rest (362.5 at 0.21), while the satellite is low.
  auto t = std::make_unique<PassTable>();
  t->begin(0, 600000);
  while (!t->complete()) {
    const float f = static_cast<float>(t->next_time()) / 600000.0f;
    LookAngles look;
    look.az_deg = std::fmod(300.0f + 300.0f * f, 360.0f);
    const float x = f < 0.75f ? (f - 0.75f) / 0.75f : (f - 0.75f) / 0.25f;
    look.el_deg = 60.0f * (1.0f - x * x);
    look.az_rate_deg_s = 1.0;
    t->add(look);
  }
  const PassPlan p = choose_plan(*t, g5500(90.0f), 300.0f, 0.0f, 2.0f, 60.0f);
  EXPECT_FALSE(p.fits);
  ASSERT_FLOAT_EQ(p.unwind_deg, -360.0f);
  const float at = static_cast<float>(p.unwind_at_ms) / 600000.0f;
  EXPECT_NEAR(at, 0.21f, 0.01f);
  EXPECT_LT(p.unwind_el_deg, 40.0f);  // leaving at the travel's end: 53
  // Each part inside the travel, continuous but for the unwind.
  float prev = 0.0f;
  for (std::int64_t ms = 0; ms <= 600000; ms += 1000) {
    float az = 0, el = 0;
    plan_position(*t, p, ms, az, el);
    EXPECT_GE(az, 0.5f) << ms;
    EXPECT_LE(az, 449.5f) << ms;
    if (ms > 0 && ms != p.unwind_at_ms) {
      EXPECT_LT(std::fabs(az - prev), 2.0f) << ms;  // 0.5 deg/s
    }
    prev = az;
  }
  // Without the unwind's duration: hold at the end (starts inside, loses least).
  const PassPlan hold = choose_plan(*t, g5500(90.0f), 300.0f, 0.0f, 2.0f);
  EXPECT_FLOAT_EQ(hold.unwind_deg, 0.0f);
  EXPECT_FALSE(hold.fits);
  EXPECT_GT(hold.held_cost, 60.0f * 90.0f * 90.0f);
}

TEST(PassPlan, RateLimitKeepsTheSlowPartsAndSpreadsAFastSwing) {
  auto t = std::make_unique<PassTable>();
  t->begin(0, 100000);
  while (!t->complete()) {
    LookAngles look;
    // A 180 deg swing within 2 s at t = 50 s.
    const double s = static_cast<double>(t->next_time()) / 1000.0;
    look.az_deg = s < 49.0 ? 180.0 : (s > 51.0 ? 0.0 : 180.0 - 90.0 * (s - 49.0));
    look.az_rate_deg_s = -1.0;
    look.el_deg = 45.0;
    t->add(look);
  }
  t->limit_rates(6.0f, 3.0f);
  float az = 0, el = 0;
  t->at(0, az, el);
  EXPECT_NEAR(az, 180.0f, 0.01f);
  t->at(50000, az, el);
  EXPECT_NEAR(az, 90.0f, 1.0f);  // midway at the swing's middle
  t->at(40000, az, el);
  EXPECT_LT(az, 180.0f);  // started early
  for (std::int64_t ms = 1000; ms <= 100000; ms += 1000) {
    float a0 = 0, a1 = 0;
    t->at(ms - 1000, a0, el);
    t->at(ms, a1, el);
    EXPECT_LE(std::fabs(a1 - a0), 6.01f) << ms;
  }
}

}  // namespace
}  // namespace rotord::tracking
