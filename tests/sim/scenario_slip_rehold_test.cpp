// slip.rehold (docs/care.md, "Slip and uncommanded motion"), on the physics
// simulator in virtual time: a rotator without a brake (the G-5500's azimuth)
// that the wind turned at rest goes back to where it came to rest, within a
// limit of re-holds; a braked one (Ham IV) never does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "care_rig.hpp"
#include "rotator/axis_events.hpp"

namespace rotord {
namespace {

using settings::Id;

/// The log lines AxisEvents writes while the rig runs (what the daemon's
/// journal and the Pico W's log port print).
struct LoggedRig {
  Rig rig;
  AxisEvents events;
  std::vector<std::string> lines;

  explicit LoggedRig(const char* profile, double az0_deg) : rig(profile, az0_deg) {
    events.begin(rig.controller().status());
  }
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      rig.tick();
      char line[200];
      while (events.next(rig.controller().status(), line, sizeof line)) lines.emplace_back(line);
    }
  }
  bool logged(const std::string& part) const {
    for (const auto& l : lines)
      if (l.find(part) != std::string::npos) return true;
    return false;
  }
};

TEST(SlipRehold, OffByDefaultASlipIsOnlyCounted) {
  LoggedRig r("g5500", 200.0);
  r.run_ms(5000);
  const float rest_deg = r.rig.az().position_deg;
  r.rig.sim().wind_slip(AxisId::kAz, 4.0, 1.0);  // 4 deg in 1 s
  r.run_ms(10000);
  EXPECT_EQ(r.rig.az().slips, 1u);
  EXPECT_EQ(r.rig.az().reholds, 0u);
  EXPECT_EQ(r.rig.az().moves, 0u);  // the motor never started
  EXPECT_NEAR(r.rig.az().position_deg, rest_deg + 4.0f, 1.0f);
  EXPECT_FALSE(r.logged("re-holding"));
}

TEST(SlipRehold, OnABrakelessAxisTurnsBackToTheRestHeading) {
  LoggedRig r("g5500", 200.0);
  r.rig.settings().set(Id::kSlipRehold, 1);
  r.run_ms(5000);
  const float rest_deg = r.rig.az().position_deg;
  const float tolerance_deg = r.rig.settings().f(Id::kAzToleranceDeg);
  r.rig.sim().wind_slip(AxisId::kAz, 4.0, 0.6);  // 2.4 deg: a slip, then calm
  Millis back_ms = -1;
  for (Millis t = 0; t < 30000 && back_ms < 0; t += 10) {
    r.run_ms(10);
    const AxisStatus& a = r.rig.az();
    if (a.reholds == 1 && !a.reholding && a.state == AxisState::kIdle) back_ms = t + 10;
  }
  r.run_ms(5000);
  const AxisStatus& a = r.rig.az();
  std::printf("rest %.2f deg, slipped to %.2f, back at %.2f deg %lld ms after the gust began\n",
              static_cast<double>(rest_deg), static_cast<double>(rest_deg + 2.4f),
              static_cast<double>(a.position_deg), static_cast<long long>(back_ms));
  ASSERT_GT(back_ms, 0);
  EXPECT_NEAR(a.position_deg, rest_deg, tolerance_deg);
  EXPECT_NEAR(a.rehold_deg, rest_deg, 0.3f);
  EXPECT_EQ(a.slips, 1u);  // the move back is no second slip
  EXPECT_EQ(a.reholds, 1u);
  EXPECT_EQ(a.reholds_refused, 0u);
  EXPECT_EQ(a.fault, AxisFault::kNone);
  char want[64];
  std::snprintf(want, sizeof want, "az: slip: re-holding %.1f deg",
                static_cast<double>(a.rehold_deg));
  EXPECT_TRUE(r.logged(want)) << want;
  for (const auto& l : r.lines) std::printf("log: %s\n", l.c_str());
}

TEST(SlipRehold, APersistentWindIsReheldAtMostThreeTimesInTenMinutes) {
  LoggedRig r("g5500", 200.0);
  r.rig.settings().set(Id::kSlipRehold, 1);
  r.run_ms(5000);
  // 2 deg/s for half a minute: each re-hold arrives, the wind turns the
  // mast again as soon as the motor is off.
  r.rig.sim().wind_slip(AxisId::kAz, 2.0, 30.0);
  r.run_ms(40000);
  const AxisStatus& a = r.rig.az();
  std::printf("30 s of wind at 2 deg/s: %u slips, %u re-holds, %u refused, left at %.1f deg\n",
              static_cast<unsigned>(a.slips), static_cast<unsigned>(a.reholds),
              static_cast<unsigned>(a.reholds_refused), static_cast<double>(a.position_deg));
  EXPECT_EQ(a.reholds, Axis::kMaxReholds);
  EXPECT_GE(a.reholds_refused, 1u);
  EXPECT_EQ(a.slips, a.reholds + a.reholds_refused);  // every slip re-held or refused
  EXPECT_GT(a.position_deg, 230.0f);                  // the wind won: no fight
  EXPECT_EQ(a.fault, AxisFault::kNone);
  EXPECT_TRUE(r.logged("az: slip: not re-holding: 3 re-holds within 10 min"));
  // Once the window has passed, a new slip is re-held again.
  r.run_ms(Axis::kReholdWindowMs);
  const float rest_deg = r.rig.az().position_deg;
  r.rig.sim().wind_slip(AxisId::kAz, 4.0, 0.6);
  r.run_ms(20000);
  EXPECT_EQ(r.rig.az().reholds, Axis::kMaxReholds + 1);
  EXPECT_NEAR(r.rig.az().position_deg, rest_deg, r.rig.settings().f(Id::kAzToleranceDeg));
}

TEST(SlipRehold, WithABrakeTheSettingDoesNothing) {
  LoggedRig r("ham4", 200.0);
  ASSERT_TRUE(r.rig.settings().b(Id::kAzHasBrake));
  r.rig.settings().set(Id::kSlipRehold, 1);
  r.run_ms(5000);
  const float rest_deg = r.rig.az().position_deg;
  r.rig.sim().wind_slip(AxisId::kAz, 4.0, 1.0);
  r.run_ms(10000);
  EXPECT_EQ(r.rig.az().slips, 1u);
  EXPECT_EQ(r.rig.az().reholds, 0u);
  EXPECT_EQ(r.rig.az().moves, 0u);
  EXPECT_NEAR(r.rig.az().position_deg, rest_deg + 4.0f, 1.0f);
  EXPECT_FALSE(r.logged("re-holding"));
}

TEST(SlipRehold, SlipFaultWinsOverTheRehold) {
  LoggedRig r("g5500", 200.0);
  r.rig.settings().set(Id::kSlipRehold, 1);
  r.rig.settings().set(Id::kSlipFault, 1);
  r.run_ms(5000);
  r.rig.sim().wind_slip(AxisId::kAz, 4.0, 1.0);
  r.run_ms(5000);
  EXPECT_EQ(r.rig.az().fault, AxisFault::kSlip);
  EXPECT_EQ(r.rig.az().reholds, 0u);
  EXPECT_EQ(r.rig.az().moves, 0u);
}

TEST(SlipRehold, StopDuringAReholdStopsIt) {
  LoggedRig r("g5500", 200.0);
  r.rig.settings().set(Id::kSlipRehold, 1);
  r.run_ms(5000);
  const float rest_deg = r.rig.az().position_deg;
  r.rig.sim().wind_slip(AxisId::kAz, 10.0, 1.0);  // 10 deg in 1 s, then calm
  // Wait until the gust is over and the motor drives back, then STOP.
  bool driving = false;
  for (Millis t = 0; t < 20000 && !driving; t += 10) {
    r.run_ms(10);
    driving = t >= 1000 && r.rig.az().reholding && r.rig.az().state == AxisState::kMoving;
  }
  ASSERT_TRUE(driving);
  const float stopped_at_deg = r.rig.az().position_deg;
  r.rig.controller().stop();
  r.run_ms(10000);
  const AxisStatus& a = r.rig.az();
  std::printf("rest %.1f deg, STOP at %.1f on the way back, stood at %.1f\n",
              static_cast<double>(rest_deg), static_cast<double>(stopped_at_deg),
              static_cast<double>(a.position_deg));
  EXPECT_FALSE(a.reholding);
  EXPECT_FALSE(a.has_target);
  EXPECT_EQ(a.state, AxisState::kIdle);
  EXPECT_EQ(a.reholds, 1u);
  EXPECT_GT(a.position_deg - rest_deg, 2.0f);         // it did not go on back
  EXPECT_NEAR(a.position_deg, stopped_at_deg, 1.5f);  // only the coast
}

}  // namespace
}  // namespace rotord
