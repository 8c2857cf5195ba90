// Slip and uncommanded motion (docs/care.md), on the physics simulator in
// virtual time: with the outputs off and the brake set, wind that turns the
// mast is an event (counted, published, shown), and with slip.fault a fault.
#include <gtest/gtest.h>

#include <cstdio>

#include "care_rig.hpp"
#include "sim/fault_window.hpp"

namespace rotord {
namespace {

/// Runs until the azimuth reports a slip (or limit_ms); the time it took.
Millis run_until_slip(Rig& r, Millis limit_ms) {
  for (Millis t = 0; t < limit_ms; t += 10) {
    r.tick();
    if (r.az().slips > 0) return t + 10;
  }
  return -1;
}

TEST(Slip, ATwoDegreeSlipAgainstTheBrakeIsFlaggedWithinASecond) {
  // A Ham IV (brake) at rest; a gust turns the mast 2 deg in 0.5 s.
  Rig r("ham4", 200.0);
  r.run_ms(5000);
  ASSERT_EQ(r.az().slips, 0u);
  r.sim().wind_slip(AxisId::kAz, 4.0, 0.5);
  const Millis after_ms = run_until_slip(r, 3000);
  std::printf("a 2 deg slip (4 deg/s for 0.5 s) flagged %lld ms after it began\n",
              static_cast<long long>(after_ms));
  ASSERT_GT(after_ms, 0);
  EXPECT_LE(after_ms, 1000);
  EXPECT_TRUE(r.az().slipping);
  EXPECT_EQ(r.az().fault, AxisFault::kNone);  // slip.fault is off by default
  // Over once the mast has stood still for a second; the axis still obeys.
  r.run_ms(2000);
  EXPECT_FALSE(r.az().slipping);
  EXPECT_EQ(r.az().slips, 1u);
  ASSERT_EQ(r.controller().go_to(150.0f, std::nullopt), Error::kOk);
  r.run_ms(30000);
  EXPECT_NEAR(r.az().position_deg, 150.0f, 1.0f);
  EXPECT_EQ(r.az().slips, 1u);  // the move is not a slip
}

TEST(Slip, ALongSlipIsOneEvent) {
  // The Ham-M story: 30 deg in 2 s against the brake.
  Rig r("ham4", 200.0);
  r.run_ms(2000);
  r.sim().wind_slip(AxisId::kAz, 15.0, 2.0);
  r.run_ms(5000);
  EXPECT_EQ(r.az().slips, 1u);
  EXPECT_NEAR(r.az().position_deg, 230.0f, 1.0f);
  // A second gust later is a second slip.
  r.sim().wind_slip(AxisId::kAz, -5.0, 1.0);
  r.run_ms(3000);
  EXPECT_EQ(r.az().slips, 2u);
}

TEST(Slip, WithSlipFaultOnASlipLatchesAFault) {
  Rig r("g5500", 200.0);
  r.settings().set(settings::Id::kSlipFault, 1);
  r.run_ms(2000);
  r.sim().wind_slip(AxisId::kAz, 3.0, 1.0);
  r.run_ms(1500);
  EXPECT_EQ(r.az().fault, AxisFault::kSlip);
  EXPECT_EQ(r.controller().go_to(100.0f, std::nullopt), Error::kFaulted);
  EXPECT_EQ(r.controller().faults_latched(AxisId::kAz, AxisFault::kSlip), 1u);
  EXPECT_EQ(r.controller().reset(), Error::kOk);
  r.run_ms(1000);
  EXPECT_EQ(r.az().fault, AxisFault::kNone);
  EXPECT_EQ(r.az().slips, 1u);
}

TEST(Slip, SmallMotionWithinTheSettingIsNoSlipAndZeroTurnsItOff) {
  Rig r("g5500", 200.0);
  r.run_ms(2000);
  r.sim().wind_slip(AxisId::kAz, 1.0, 1.5);  // 1.5 deg: under slip.deg (2)
  r.run_ms(3000);
  EXPECT_EQ(r.az().slips, 0u);
  r.settings().set(settings::Id::kSlipDeg, 0);
  r.sim().wind_slip(AxisId::kAz, 5.0, 2.0);
  r.run_ms(3000);
  EXPECT_EQ(r.az().slips, 0u);
}

TEST(Slip, TheCoastAfterAStopIsNoSlip) {
  // A G-5500 coasts ~1 deg after its relay drops; the stop is judged at rest
  // before the axis counts as idle.
  Rig r("g5500", 200.0);
  for (float target : {300.0f, 100.0f, 105.0f, 420.0f, 10.0f}) {
    ASSERT_EQ(r.controller().go_to(target, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
    r.run_ms(90000);
  }
  EXPECT_EQ(r.az().slips, 0u);
}

}  // namespace
}  // namespace rotord
