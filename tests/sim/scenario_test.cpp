// Whole-controller scenarios on the physics simulator, in virtual time: the
// controller core exactly as the daemon runs it, against the three rotator
// profiles (coast, backlash, relay delay, sensor noise, end stops).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "rotator/controller.hpp"
#include "sim/fault_window.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "sim_bench.hpp"

namespace rotord {
namespace {

/// The shared bench (sim_bench.hpp), counting the ticks both azimuth relays
/// are on and the plant is stalled, and the azimuth's extent.
class Scenario : public testing::SimBench {
 public:
  Scenario(const char* profile_name, double az0_deg, double el0_deg = 0.0)
      : Scenario(*sim::find_profile(profile_name), az0_deg, el0_deg) {}
  /// A variation of a built-in profile (another drive, say), kept by the scenario.
  Scenario(const sim::Profile& profile, double az0_deg, double el0_deg = 0.0)
      : SimBench(profile, 11, az0_deg, el0_deg) {
    power_on();
  }

  /// Runs until both axes are idle with no target (or the time runs out).
  bool run_until_settled(Millis limit_ms) {
    for (Millis t = 0; t < limit_ms; t += 100) {
      run_ms(100);
      const RotatorStatus s = status();
      const bool az_done = !s.az.has_target && s.az.state == AxisState::kIdle;
      const bool el_done = !s.el.present || (!s.el.has_target && s.el.state == AxisState::kIdle);
      if (az_done && el_done) return true;
    }
    return false;
  }

  struct Reversal {
    bool reversed = false;
    Millis unpowered_ms = 0;  // neither direction relay on, before CCW came on
    double speed_at_reversal_deg_s = 0.0;
  };
  /// Runs until the azimuth's CCW relay comes on (at most limit_ms).
  Reversal run_until_ccw(Millis limit_ms) {
    Reversal r;
    for (Millis t = 0; t < limit_ms && !r.reversed; t += 10) {
      run_ms(10);
      const DriveOutputs& out = sim().outputs(AxisId::kAz);
      if (out.on(OutputChannel::kRelayCcw)) {
        r.reversed = true;
        r.speed_at_reversal_deg_s = sim().plant(AxisId::kAz).w_deg_s();
      } else if (!out.on(OutputChannel::kRelayCw)) {
        r.unpowered_ms += 10;
      }
    }
    return r;
  }

  int both_relays_ticks() const { return both_relays_ticks_; }
  int stalled_ticks() const { return stalled_ticks_; }
  double max_az() const { return max_az_; }
  double min_az() const { return min_az_; }

 private:
  void on_tick() override {
    const DriveOutputs& az = sim().outputs(AxisId::kAz);
    if (az.on(OutputChannel::kRelayCw) && az.on(OutputChannel::kRelayCcw)) ++both_relays_ticks_;
    if (sim().plant(AxisId::kAz).stalled()) ++stalled_ticks_;
    max_az_ = std::max(max_az_, theta(AxisId::kAz));
    min_az_ = std::min(min_az_, theta(AxisId::kAz));
  }

  int both_relays_ticks_ = 0;
  int stalled_ticks_ = 0;
  double max_az_ = -1e9;
  double min_az_ = 1e9;
};

TEST(Scenario, G5500GotoArrivesWithinToleranceOnBothAxes) {
  Scenario s("g5500", 100.0, 10.0);
  ASSERT_EQ(s.controller().go_to(200.0f, 45.0f), Error::kOk);
  ASSERT_TRUE(s.run_until_settled(120000));
  EXPECT_NEAR(s.theta(AxisId::kAz), 200.0, 1.0);
  EXPECT_NEAR(s.theta(AxisId::kEl), 45.0, 1.0);
  EXPECT_LE(s.status().az.moves, 2u);  // at most one correction
  EXPECT_LE(s.status().el.moves, 2u);
  EXPECT_EQ(s.both_relays_ticks(), 0);
}

TEST(Scenario, GotoClockwiseIntoTheOverlap) {
  // At 350, compass 60 is 70 deg away at 420 through 360, 290 deg away at 60.
  Scenario s("g5500", 350.0);
  ASSERT_EQ(s.controller().go_to(60.0f, std::nullopt), Error::kOk);
  EXPECT_FLOAT_EQ(s.status().az.target_deg, 420.0f);
  ASSERT_TRUE(s.run_until_settled(60000));
  EXPECT_NEAR(s.theta(AxisId::kAz), 420.0, 1.0);
  EXPECT_GE(s.min_az(), 349.0);                           // never went the long way
  EXPECT_NEAR(s.status().az.position_deg, 420.0f, 1.5f);  // reported unwrapped, not 60
}

TEST(Scenario, GotoCounterClockwiseOutOfTheOverlap) {
  Scenario s("g5500", 420.0);
  ASSERT_EQ(s.controller().go_to(300.0f, std::nullopt), Error::kOk);
  ASSERT_TRUE(s.run_until_settled(60000));
  EXPECT_NEAR(s.theta(AxisId::kAz), 300.0, 1.0);
  EXPECT_LE(s.max_az(), 421.0);
}

TEST(Scenario, ReversalDuringAMoveStopsWaitsAndTurnsBack) {
  Scenario s("g5500", 100.0);
  s.settings().set(settings::Id::kAzReverseDeadMs, 1500);
  ASSERT_EQ(s.controller().go_to(300.0f, std::nullopt), Error::kOk);
  s.run_ms(5000);
  ASSERT_GT(s.theta(AxisId::kAz), 110.0);
  ASSERT_EQ(s.controller().go_to(80.0f, std::nullopt), Error::kOk);
  // The motor must be unpowered and at rest before it is driven the other way.
  const Scenario::Reversal r = s.run_until_ccw(10000);
  ASSERT_TRUE(r.reversed);
  EXPECT_NEAR(r.speed_at_reversal_deg_s, 0.0, 0.05);
  EXPECT_GE(r.unpowered_ms, 1500);
  ASSERT_TRUE(s.run_until_settled(120000));
  EXPECT_NEAR(s.theta(AxisId::kAz), 80.0, 1.0);
  EXPECT_EQ(s.both_relays_ticks(), 0);
}

TEST(Scenario, JogStopsBeforeTheEndStopAndTheLimitSwitch) {
  Scenario s("ham4", 300.0);
  ASSERT_EQ(s.controller().move(AxisId::kAz, Direction::kCw), Error::kOk);
  s.run_ms(30000);
  EXPECT_FALSE(s.sim().plant(AxisId::kAz).powered());
  EXPECT_LE(s.max_az(), 360.5);
  EXPECT_GT(s.theta(AxisId::kAz), 355.0);
  EXPECT_EQ(s.stalled_ticks(), 0);  // never drove against the mechanical stop
  EXPECT_EQ(s.controller().move(AxisId::kAz, Direction::kCw), Error::kLimit);
}

TEST(Scenario, LimitSwitchStopsTheMotorEvenBeyondTheSoftLimit) {
  // A mis-set soft limit (beyond the switch) must not matter: the switch wins.
  Scenario s("ham4", 340.0);
  s.settings().set(settings::Id::kAzMaxDeg, 400);
  ASSERT_EQ(s.controller().move(AxisId::kAz, Direction::kCw), Error::kOk);
  s.run_ms(30000);
  EXPECT_FALSE(s.sim().plant(AxisId::kAz).powered());
  EXPECT_TRUE(s.status().az.switch_cw);
  EXPECT_EQ(s.stalled_ticks(), 0);
}

TEST(Scenario, JamLatchesAStallFault) {
  Scenario s("g5500", 100.0);
  ASSERT_EQ(s.controller().go_to(250.0f, std::nullopt), Error::kOk);
  s.run_ms(3000);
  s.sim().jam(AxisId::kAz, sim::kForever_s);
  s.run_ms(6000);
  EXPECT_EQ(s.status().az.fault, AxisFault::kStall);
  EXPECT_FALSE(s.sim().outputs(AxisId::kAz).any_on());
  EXPECT_EQ(s.controller().go_to(10.0f, std::nullopt), Error::kFaulted);
}

TEST(Scenario, SensorLossLatchesAFaultAndStops) {
  Scenario s("g5500", 100.0);
  ASSERT_EQ(s.controller().go_to(250.0f, std::nullopt), Error::kOk);
  s.run_ms(3000);
  s.sim().sensor_loss(AxisId::kAz, sim::kForever_s);
  s.run_ms(1000);
  EXPECT_NE(s.status().az.fault, AxisFault::kNone);
  EXPECT_FALSE(s.sim().plant(AxisId::kAz).powered());
  const double at_fault = s.theta(AxisId::kAz);
  s.run_ms(5000);
  EXPECT_NEAR(s.theta(AxisId::kAz), at_fault, 2.0);  // coasted to rest, not driven
}

TEST(Scenario, Ma3SensorLossOnSpid) {
  Scenario s("spid", 0.0, 10.0);
  ASSERT_EQ(s.controller().go_to(200.0f, std::nullopt), Error::kOk);
  s.run_ms(2000);
  s.sim().sensor_loss(AxisId::kAz, sim::kForever_s);
  s.run_ms(1000);
  EXPECT_EQ(s.status().az.fault, AxisFault::kSensorLost);
  EXPECT_FALSE(s.sim().plant(AxisId::kAz).powered());
}

TEST(Scenario, StopDuringTheBrakeReleaseNeverPowersTheMotor) {
  Scenario s("ham4", 100.0);
  ASSERT_TRUE(s.settings().b(settings::Id::kAzHasBrake));
  ASSERT_EQ(s.controller().go_to(200.0f, std::nullopt), Error::kOk);
  s.run_ms(100);
  EXPECT_TRUE(s.sim().outputs(AxisId::kAz).on(OutputChannel::kBrake));
  EXPECT_FALSE(s.sim().plant(AxisId::kAz).powered());
  s.controller().stop();
  s.run_ms(10000);
  EXPECT_FALSE(s.sim().outputs(AxisId::kAz).any_on());  // brake engaged again
  EXPECT_NEAR(s.theta(AxisId::kAz), 100.0, 0.01);
}

TEST(Scenario, BrakeIsReleasedBeforeDriveAndEngagedAfterTheCoast) {
  Scenario s("ham4", 100.0);
  ASSERT_EQ(s.controller().go_to(150.0f, std::nullopt), Error::kOk);
  bool drove_with_brake_on = false;
  bool brake_dropped_while_turning = false;
  for (int n = 0; n < 6000; ++n) {
    s.run_ms(10);
    const DriveOutputs& out = s.sim().outputs(AxisId::kAz);
    const bool driving = out.on(OutputChannel::kRelayCw) || out.on(OutputChannel::kRelayCcw);
    if (driving && !out.on(OutputChannel::kBrake)) drove_with_brake_on = true;
    if (!out.on(OutputChannel::kBrake) && std::fabs(s.sim().plant(AxisId::kAz).w_deg_s()) > 0.5)
      brake_dropped_while_turning = true;
  }
  EXPECT_FALSE(drove_with_brake_on);
  EXPECT_FALSE(brake_dropped_while_turning);
  EXPECT_NEAR(s.theta(AxisId::kAz), 150.0, 1.0);
}

TEST(Scenario, SpidReachesUnwrappedTargetsAcrossItsWholeTravel) {
  Scenario s("spid", 0.0, 10.0);
  ASSERT_EQ(s.controller().go_to(-100.0f, 170.0f), Error::kOk);
  ASSERT_TRUE(s.run_until_settled(120000));
  EXPECT_NEAR(s.theta(AxisId::kAz), -100.0, 1.0);
  EXPECT_NEAR(s.theta(AxisId::kEl), 170.0, 1.0);
  ASSERT_EQ(s.controller().go_to(500.0f, std::nullopt), Error::kOk);
  ASSERT_TRUE(s.run_until_settled(240000));
  EXPECT_NEAR(s.theta(AxisId::kAz), 500.0, 1.0);
  EXPECT_NEAR(s.status().az.position_deg, 500.0f, 1.0f);
}

TEST(Scenario, PowerCutInTheOverlapKeepsTheUnwrappedPosition) {
  // MA3 is single-turn: after a restart at 400 deg it reads 40; the T1
  // threshold input tells the controller it is in the CW overlap.
  Scenario s("spid", 400.0, 10.0);
  s.run_ms(100);
  EXPECT_NEAR(s.status().az.position_deg, 400.0f, 1.0f);
  s.power_on();
  s.run_ms(100);
  EXPECT_NEAR(s.status().az.position_deg, 400.0f, 1.0f);
  EXPECT_FALSE(s.sim().outputs(AxisId::kAz).any_on());
}

TEST(Scenario, SmallMovesDoNotHunt) {
  Scenario s("g5500", 100.0);
  float target = 100.0f;
  for (int n = 0; n < 10; ++n) {
    target += 3.0f;
    ASSERT_EQ(s.controller().go_to(target, std::nullopt), Error::kOk);
    ASSERT_TRUE(s.run_until_settled(30000));
    EXPECT_NEAR(s.theta(AxisId::kAz), target, 1.5) << "step " << n;
  }
  // Ten 3 deg steps: at most one correction each.
  EXPECT_LE(s.status().az.moves, 20u);
}

// A G-5500 wired with a speed relay: two-speed windings or a voltage-select
// supply, the slow one at half speed.
sim::Profile g5500_with_drive(sim::DriveKind drive) {
  sim::Profile p = *sim::find_profile("g5500");
  p.az.plant.drive = drive;
  return p;
}

// A soft stop runs the motor on for az.soft_ms (plus the direction relay's
// settle time on a voltage-select drive) before the coast: the stop is cut
// that much earlier, so the antenna still ends on the target, in one move.
TEST(Scenario, SoftStopsEndOnTheTargetWithoutACorrection) {
  struct Case {
    sim::Profile profile;
    int drive;
    int soft_ms;
  };
  const Case cases[] = {
      {g5500_with_drive(sim::DriveKind::kRelayTwoSpeed), 1, 500},
      {g5500_with_drive(sim::DriveKind::kRelayVoltageSelect), 2, 500},
      {g5500_with_drive(sim::DriveKind::kRelayVoltageSelect), 2, 2000},
      {*sim::find_profile("spid"), 3, 1000},
  };
  for (const Case& c : cases) {
    Scenario s(c.profile, 100.0, 10.0);
    s.settings().set(settings::Id::kAzDrive, c.drive);
    s.settings().set(settings::Id::kAzSoftMs, c.soft_ms);
    s.power_on();
    ASSERT_EQ(s.controller().go_to(160.0f, std::nullopt), Error::kOk);
    ASSERT_TRUE(s.run_until_settled(120000));
    EXPECT_NEAR(s.theta(AxisId::kAz), 160.0, 1.0) << "drive " << c.drive << ", soft " << c.soft_ms;
    EXPECT_EQ(s.status().az.moves, 1u) << "drive " << c.drive << ", soft " << c.soft_ms;
    EXPECT_LE(s.max_az(), 161.0) << "drive " << c.drive << ", soft " << c.soft_ms;
  }
}

// A jog to the end of the travel with a long soft stop: the run-on (at the
// slow speed az.slow_speed_ratio says) is part of the stopping distance, so
// the antenna stops inside az.max_deg.
TEST(Scenario, ASoftStopNeverRunsPastTheEndOfTheTravel) {
  Scenario s(g5500_with_drive(sim::DriveKind::kRelayVoltageSelect), 400.0, 10.0);
  s.settings().set(settings::Id::kAzDrive, 2);
  s.settings().set(settings::Id::kAzSoftMs, 3000);
  s.settings().set(settings::Id::kAzSlowSpeedRatio, 0.5f);  // the creep supply's, as measured
  s.power_on();
  ASSERT_EQ(s.controller().move(AxisId::kAz, Direction::kCw), Error::kOk);
  s.run_ms(30000);
  EXPECT_FALSE(s.sim().plant(AxisId::kAz).powered());
  EXPECT_LE(s.max_az(), 450.5);  // as a jog without a soft stop (ham4 above)
  EXPECT_GT(s.theta(AxisId::kAz), 440.0);
  EXPECT_FALSE(s.status().az.switch_cw);
  EXPECT_EQ(s.stalled_ticks(), 0);
}

// A reversal on a voltage-select drive with a 2 s soft stop: the motor runs
// on at creep, then coasts; the other direction comes only at rest, after
// the dead time, and the target behind is reached.
TEST(Scenario, ASoftReversalWaitsForTheRunOnTheCoastAndTheDeadTime) {
  Scenario s(g5500_with_drive(sim::DriveKind::kRelayVoltageSelect), 100.0, 10.0);
  s.settings().set(settings::Id::kAzDrive, 2);
  s.settings().set(settings::Id::kAzSoftMs, 2000);
  s.settings().set(settings::Id::kAzSlowSpeedRatio, 0.5f);
  s.power_on();
  ASSERT_EQ(s.controller().go_to(300.0f, std::nullopt), Error::kOk);
  s.run_ms(8000);
  ASSERT_GT(s.theta(AxisId::kAz), 120.0);
  ASSERT_EQ(s.controller().go_to(80.0f, std::nullopt), Error::kOk);
  const Scenario::Reversal r = s.run_until_ccw(20000);
  ASSERT_TRUE(r.reversed);
  EXPECT_NEAR(r.speed_at_reversal_deg_s, 0.0, 0.05);
  EXPECT_GE(r.unpowered_ms, 1000);  // az.reverse_dead_ms, at rest
  ASSERT_TRUE(s.run_until_settled(120000));
  EXPECT_NEAR(s.theta(AxisId::kAz), 80.0, 1.0);
  EXPECT_EQ(s.status().az.moves, 2u);
  EXPECT_EQ(s.both_relays_ticks(), 0);
}

TEST(Scenario, SpidCrossesItsWholeTravelAtEveryAllowedSpeed) {
  // Issue 10: at speed 50 a 720 deg move took longer than the fixed 180 s
  // timeout and latched TIMEOUT part way. The allowance now follows from the
  // distance and the speed that speed achieves above the PWM dead band.
  for (const int speed_pct : {1, 25, 50, 100}) {
    Scenario s("spid", 540.0, 10.0);
    s.run_ms(100);
    ASSERT_EQ(s.controller().set_speed_pct(speed_pct), Error::kOk);
    ASSERT_EQ(s.controller().go_to(-180.0f, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
    ASSERT_TRUE(s.run_until_settled(1800000)) << "speed " << speed_pct;
    EXPECT_EQ(s.status().az.fault, AxisFault::kNone) << "speed " << speed_pct;
    EXPECT_NEAR(s.theta(AxisId::kAz), -180.0, 1.0) << "speed " << speed_pct;
  }
}

TEST(Scenario, ASlippingRotatorStillTimesOut) {
  // A slipping clutch turns at a fifth of the speed: too fast for the stall
  // rule, far too slow for the move; the timeout stops it.
  Scenario s("spid", 0.0, 10.0);
  s.sim().slip(AxisId::kAz, 0.2, sim::kForever_s);
  ASSERT_EQ(s.controller().go_to(500.0f, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
  s.run_until_settled(600000);
  EXPECT_EQ(s.status().az.fault, AxisFault::kTimeout);
  EXPECT_LT(s.theta(AxisId::kAz), 480.0);
  EXPECT_FALSE(s.sim().outputs(AxisId::kAz).any_on());
}

}  // namespace
}  // namespace rotord
