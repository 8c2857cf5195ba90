// The axis state machine and the controller's command rules on fake
// hardware. The test is the plant: each tick it moves the pot by the drive's
// direction at a fixed rate (no coast), so every decision can be checked
// tick by tick.
#include <gtest/gtest.h>

#include "fake_rotator.hpp"

namespace rotord {
namespace {

using settings::Id;
using testing::FakeAxisHardware;
using testing::FakeRotator;

class ControllerTest : public ::testing::Test {
 protected:
  FakeRotator r;
  float az_deg = 100.0f;
  float el_deg = 20.0f;
  float rate_deg_per_tick = 0.06f;  // 6 deg/s at 100 Hz
  int both_on_ticks = 0;

  void SetUp() override { r.settings.set(Id::kAzReverseDeadMs, 500); }

  /// Runs ticks with the fake plant following the relays.
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      follow(r.az, az_deg);
      follow(r.el, el_deg);
      r.now += 10;
      r.controller->tick(r.now);
    }
  }
  void follow(FakeAxisHardware& hw, float& deg) {
    if (hw.drive.cw() && hw.drive.ccw()) ++both_on_ticks;
    if (hw.drive.cw()) deg += rate_deg_per_tick;
    if (hw.drive.ccw()) deg -= rate_deg_per_tick;
    hw.set_deg(deg);
  }
  RotatorStatus status() { return r.controller->status(); }
  /// A go-to from rest (the gate narrowed to its floor by a second of
  /// readings), run until the CW relay is on; then a control loop held up
  /// for `stall_ms` while the pot moved by `moved_deg`, and one tick.
  void stall_just_after_a_cw_start(Millis stall_ms, float moved_deg) {
    run_ms(1000);
    ASSERT_EQ(r.controller->go_to(130.0f, std::nullopt), Error::kOk);
    for (int n = 0; n < 200 && !r.az.drive.cw(); ++n) run_ms(10);
    ASSERT_TRUE(r.az.drive.cw());
    az_deg += moved_deg;
    r.az.set_deg(az_deg);
    r.now += stall_ms;
    r.controller->tick(r.now);
  }
  /// Power-cycles the controller with the antenna at `deg` (a jump of the
  /// pot while running would rightly be taken for a sensor fault).
  void restart_at(float deg) {
    az_deg = deg;
    r.az.set_deg(deg);
    r.controller = std::make_unique<Controller>(r.settings, r.az.io(), r.el.io());
    r.controller->begin(r.now);
  }
};

TEST_F(ControllerTest, OutputsAreOffAtStart) {
  EXPECT_GE(r.az.drive.applies, 1);
  EXPECT_FALSE(r.az.drive.last.any_on());
  EXPECT_FALSE(r.el.drive.last.any_on());
  EXPECT_FLOAT_EQ(status().az.position_deg, 100.0f);
}

TEST_F(ControllerTest, GotoArrivesWithinToleranceWithoutHunting) {
  ASSERT_EQ(r.controller->go_to(200.0f, 45.0f), Error::kOk);
  run_ms(40000);
  const RotatorStatus s = status();
  EXPECT_NEAR(s.az.position_deg, 200.0f, 1.0f);
  EXPECT_NEAR(s.el.position_deg, 45.0f, 1.0f);
  EXPECT_EQ(s.az.state, AxisState::kIdle);
  EXPECT_TRUE(s.az.arrived);
  EXPECT_EQ(s.az.moves, 1u);  // one start, no correction on an exact plant
  EXPECT_EQ(s.mode, Mode::kIdle);
  EXPECT_FALSE(r.az.drive.last.any_on());
}

TEST_F(ControllerTest, CompassTargetUsesTheOverlap) {
  restart_at(400.0f);
  run_ms(100);
  ASSERT_EQ(r.controller->go_to(60.0f, std::nullopt), Error::kOk);
  EXPECT_FLOAT_EQ(status().az.target_deg, 420.0f);
  run_ms(1000);
  EXPECT_TRUE(r.az.drive.cw());  // 400 -> 420 turns CW, not 340 deg back
  run_ms(10000);
  EXPECT_NEAR(status().az.position_deg, 420.0f, 1.0f);
}

TEST_F(ControllerTest, UnwrappedTargetIsHonouredAsGiven) {
  restart_at(400.0f);
  run_ms(100);
  ASSERT_EQ(r.controller->go_to(60.0f, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
  EXPECT_FLOAT_EQ(status().az.target_deg, 60.0f);
  ASSERT_EQ(r.controller->go_to(430.0f, std::nullopt), Error::kOk);  // > 360: unwrapped
  EXPECT_FLOAT_EQ(status().az.target_deg, 430.0f);
}

TEST_F(ControllerTest, OutOfRangeTargetsChangeNothing) {
  EXPECT_EQ(r.controller->go_to(451.0f, std::nullopt), Error::kOutOfRange);
  EXPECT_EQ(r.controller->go_to(-5.0f, std::nullopt), Error::kOutOfRange);
  // Both axes are validated before either moves.
  EXPECT_EQ(r.controller->go_to(200.0f, 181.0f), Error::kOutOfRange);
  run_ms(2000);
  EXPECT_FALSE(status().az.has_target);
  EXPECT_EQ(status().az.moves, 0u);
  EXPECT_FALSE(r.az.drive.last.any_on());
}

TEST_F(ControllerTest, ElevationOnAzimuthOnlyRotatorIsNotSupported) {
  FakeRotator az_only(false);
  EXPECT_EQ(az_only.controller->go_to(10.0f, 10.0f), Error::kNotSupported);
  EXPECT_EQ(az_only.controller->move(AxisId::kEl, Direction::kCw), Error::kNotSupported);
  EXPECT_FALSE(az_only.controller->status().el.present);
}

TEST_F(ControllerTest, ReversalPassesThroughStopAndDeadTime) {
  ASSERT_EQ(r.controller->go_to(300.0f, std::nullopt), Error::kOk);
  run_ms(2000);
  ASSERT_TRUE(r.az.drive.cw());
  ASSERT_EQ(r.controller->go_to(50.0f, std::nullopt), Error::kOk);
  // Count the ticks with no drive between the CW and the CCW phase.
  Millis off_ms = 0;
  bool saw_ccw = false;
  for (int t = 0; t < 500 && !saw_ccw; ++t) {
    run_ms(10);
    if (r.az.drive.ccw())
      saw_ccw = true;
    else if (!r.az.drive.cw())
      off_ms += 10;
    if (!saw_ccw && !r.az.drive.cw()) {
      const auto state = status().az.state;
      EXPECT_TRUE(state == AxisState::kReversing || state == AxisState::kIdle ||
                  state == AxisState::kStarting)
          << axis_state_name(state);
    }
  }
  EXPECT_TRUE(saw_ccw);
  EXPECT_GE(off_ms, 500);
  EXPECT_EQ(both_on_ticks, 0);
  run_ms(60000);
  EXPECT_NEAR(status().az.position_deg, 50.0f, 1.0f);
}

TEST_F(ControllerTest, LimitSwitchStopsThatDirectionOnly) {
  ASSERT_EQ(r.controller->move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(500);
  ASSERT_TRUE(r.az.drive.cw());
  r.az.limit_cw.on = true;
  run_ms(10);
  EXPECT_FALSE(r.az.drive.cw());  // cut on the first tick
  EXPECT_EQ(r.controller->move(AxisId::kAz, Direction::kCw), Error::kLimit);
  run_ms(2000);
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_TRUE(status().az.limit_cw);
  EXPECT_EQ(r.controller->move(AxisId::kAz, Direction::kCcw), Error::kOk);
  run_ms(2000);
  EXPECT_TRUE(r.az.drive.ccw());
}

TEST_F(ControllerTest, JogStopsAtTheSoftLimit) {
  restart_at(440.0f);
  run_ms(100);
  ASSERT_EQ(r.controller->move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(5000);
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_LE(az_deg, 450.0f);
  EXPECT_GT(az_deg, 448.0f);
}

TEST_F(ControllerTest, StallLatchesAFaultThatStopsEverything) {
  rate_deg_per_tick = 0.0f;  // jammed
  ASSERT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
  run_ms(2000);
  EXPECT_TRUE(r.az.drive.cw());
  run_ms(3000);
  const RotatorStatus s = status();
  EXPECT_EQ(s.az.fault, AxisFault::kStall);
  EXPECT_EQ(s.az.state, AxisState::kFault);
  EXPECT_FALSE(r.az.drive.last.any_on());
  EXPECT_EQ(r.controller->go_to(150.0f, std::nullopt), Error::kFaulted);
  EXPECT_EQ(r.controller->move(AxisId::kAz, Direction::kCcw), Error::kFaulted);
  run_ms(1000);
  EXPECT_FALSE(r.az.drive.last.any_on());
  r.controller->reset();
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  rate_deg_per_tick = 0.06f;
  EXPECT_EQ(r.controller->go_to(110.0f, std::nullopt), Error::kOk);
  run_ms(5000);
  EXPECT_NEAR(status().az.position_deg, 110.0f, 1.0f);
}

TEST_F(ControllerTest, OpenPotIsASensorFault) {
  ASSERT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
  run_ms(1000);
  r.az.adc.counts = 0;  // wiper open: the ADC reads the rail
  for (int t = 0; t < 50; ++t) {
    r.now += 10;
    r.controller->tick(r.now);
  }
  EXPECT_EQ(status().az.fault, AxisFault::kSensorRange);
  EXPECT_FALSE(r.az.drive.last.any_on());
}

TEST_F(ControllerTest, ImplausibleJumpsAreRejectedThenLatched) {
  run_ms(100);
  // One spike is ignored.
  r.az.set_deg(300.0f);
  r.now += 10;
  r.controller->tick(r.now);
  r.az.set_deg(100.0f);
  run_ms(100);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  EXPECT_NEAR(status().az.position_deg, 100.0f, 0.2f);
  // A reading that stays implausible latches a fault.
  r.az.set_deg(300.0f);
  for (int t = 0; t < 10; ++t) {
    r.now += 10;
    r.controller->tick(r.now);
  }
  EXPECT_EQ(status().az.fault, AxisFault::kSensorJump);
}

TEST_F(ControllerTest, ALoopStallJustAfterAStartIsMotionNotASensorJump) {
  // As on the emulated Pi of tests/pi_vm, whose loop stalls for half a
  // second and more. Before, the gate allowed a reading after a stall at
  // most 250 ms of the rated speed (2 deg in all): the pot's reading, 3.6
  // deg on, was rejected, the prediction stayed at rest (no speed measured
  // yet) and SENSOR_JUMP latched on a good sensor.
  stall_just_after_a_cw_start(600, rate_deg_per_tick * 60.0f);  // 6 deg/s
  run_ms(300);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  EXPECT_EQ(status().az.readings_rejected, 0u);
  run_ms(10000);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  EXPECT_NEAR(status().az.position_deg, 130.0f, 1.0f);
  EXPECT_TRUE(status().az.arrived);
}

TEST_F(ControllerTest, AReadingFartherThanTheMotorCouldTurnInAStallIsStillAJump) {
  // What the rated speed covers in the stall, 3.6 deg in 600 ms (plus the
  // gate's 0.5 deg floor), and no more: 8 deg is a jump.
  stall_just_after_a_cw_start(600, 8.0f);
  rate_deg_per_tick = 0.0f;  // the pot stays where the jump put it
  run_ms(300);
  EXPECT_EQ(status().az.fault, AxisFault::kSensorJump);
  EXPECT_FALSE(r.az.drive.last.any_on());
}

TEST_F(ControllerTest, RecalibratingThePotMovesThePositionWithoutAJumpFault) {
  run_ms(100);
  const AxisStatus before = status().az;
  EXPECT_EQ(before.raw_full_scale, 8191.0f);  // the fake's 13-bit converter
  EXPECT_FLOAT_EQ(before.adc_ref_v, 3.3f);
  // "The antenna now points at 0": the low point moves to the live reading.
  r.settings.set(Id::kAzPotCalLoCounts, before.raw);
  r.settings.set(Id::kAzPotCalLoDeg, 0);
  run_ms(200);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  EXPECT_NEAR(status().az.position_deg, 0.0f, 0.2f);
  // The axis still tells real jumps from calibrations.
  az_deg = 300.0f;
  run_ms(100);
  EXPECT_EQ(status().az.fault, AxisFault::kSensorJump);
}

TEST_F(ControllerTest, SwitchingBackToThePotForgetsItsOldReadings) {
  run_ms(100);
  r.settings.set(Id::kAzSensor, 1);  // MA3 for a while; the pot is not read
  run_ms(100);
  az_deg = 150.0f;  // the rotator turned meanwhile
  r.settings.set(Id::kAzSensor, 0);
  run_ms(200);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  EXPECT_NEAR(status().az.position_deg, 150.0f, 0.2f);
}

TEST_F(ControllerTest, StopDuringBrakeReleaseNeverDrivesTheMotor) {
  r.settings.set(Id::kAzHasBrake, 1);  // needs-restart setting: rebuild
  r.settings.set(Id::kAzBrakeReleaseMs, 1000);
  r.settings.set(Id::kAzBrakeEngageMs, 500);
  r.controller = std::make_unique<Controller>(r.settings, r.az.io(), r.el.io());
  r.controller->begin(r.now);
  ASSERT_EQ(r.controller->move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(300);
  EXPECT_TRUE(r.az.drive.last.on(OutputChannel::kBrake));
  EXPECT_FALSE(r.az.drive.cw());
  r.controller->stop();
  run_ms(3000);
  EXPECT_FALSE(r.az.drive.last.any_on());
  EXPECT_FLOAT_EQ(az_deg, 100.0f);
  EXPECT_EQ(status().az.state, AxisState::kIdle);
}

TEST_F(ControllerTest, DeadManStopsAHeldMoveWhenRenewalsStop) {
  ASSERT_EQ(r.controller->move(AxisId::kAz, Direction::kCw, -1, 500), Error::kOk);
  run_ms(300);
  EXPECT_TRUE(r.az.drive.cw());
  // Renewed once...
  ASSERT_EQ(r.controller->move(AxisId::kAz, Direction::kCw, -1, 500), Error::kOk);
  run_ms(400);
  EXPECT_TRUE(r.az.drive.cw());
  // ...then the client vanishes.
  run_ms(200);
  EXPECT_FALSE(r.az.drive.cw());
}

TEST_F(ControllerTest, ShutdownTurnsEverythingOff) {
  ASSERT_EQ(r.controller->move(AxisId::kAz, Direction::kCcw), Error::kOk);
  ASSERT_EQ(r.controller->move(AxisId::kEl, Direction::kCw), Error::kOk);
  run_ms(500);
  ASSERT_TRUE(r.az.drive.ccw());
  r.controller->shutdown();
  EXPECT_FALSE(r.az.drive.last.any_on());
  EXPECT_FALSE(r.el.drive.last.any_on());
}

TEST_F(ControllerTest, ParkGoesToTheConfiguredPosition) {
  r.settings.set(Id::kParkAzDeg, 180);
  r.settings.set(Id::kParkElDeg, 90);
  ASSERT_EQ(r.controller->park(), Error::kOk);
  EXPECT_EQ(status().mode, Mode::kPark);
  run_ms(40000);
  EXPECT_NEAR(status().az.position_deg, 180.0f, 1.0f);
  EXPECT_NEAR(status().el.position_deg, 90.0f, 1.0f);
}

TEST_F(ControllerTest, SpeedIsValidated) {
  EXPECT_EQ(r.controller->set_speed_pct(0), Error::kOutOfRange);
  EXPECT_EQ(r.controller->set_speed_pct(101), Error::kOutOfRange);
  EXPECT_EQ(r.controller->set_speed_pct(80), Error::kOk);
  EXPECT_EQ(status().speed_pct, 80);
}

TEST_F(ControllerTest, AMoveFarSlowerThanRatedLatchesATimeout) {
  // Rated 6 deg/s, so 200 deg may take 2 x 33 s + 10 s + three starts'
  // dead times: about 81 s. A slipping rotator making 1 deg/s is slow but
  // never stalled; the timeout stops it.
  r.settings.set(Id::kAzMoveTimeoutS, 5);
  r.settings.set(Id::kAzSpeedDegS, 6.0);
  rate_deg_per_tick = 0.01f;
  ASSERT_EQ(r.controller->go_to(300.0f, std::nullopt), Error::kOk);
  run_ms(75000);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  run_ms(10000);
  EXPECT_EQ(status().az.fault, AxisFault::kTimeout);
  EXPECT_FALSE(r.az.drive.last.any_on());
}

TEST_F(ControllerTest, TheShortestTimeoutIsTheConfiguredOne) {
  // 100 deg at a rated 6 deg/s is allowed about 47 s; a configured 60 s
  // still applies above that.
  r.settings.set(Id::kAzMoveTimeoutS, 60);
  rate_deg_per_tick = 0.01f;  // 1 deg/s
  ASSERT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
  run_ms(58000);
  EXPECT_EQ(status().az.fault, AxisFault::kNone);
  run_ms(4000);
  EXPECT_EQ(status().az.fault, AxisFault::kTimeout);
}

TEST_F(ControllerTest, ContinuousRotatorTakesTheShortWayThroughNorth) {
  // A slip-ring rotator with a single-turn encoder: 350 -> 10 turns CW 20 deg.
  r.settings.set(Id::kAzContinuous, 1);
  r.settings.set(Id::kAzSensor, 1);
  const auto ma3_at = [this](float deg) {
    const auto high = static_cast<std::uint32_t>(deg / 360.0f * 4098.0f + 1.0f);
    r.az.ma3.period = {high, 4098 - high, true};
  };
  ma3_at(350.0f);
  r.controller = std::make_unique<Controller>(r.settings, r.az.io(), r.el.io());
  r.controller->begin(r.now);
  run_ms(50);
  EXPECT_NEAR(status().az.position_deg, 350.0f, 0.2f);
  ASSERT_EQ(r.controller->go_to(10.0f, std::nullopt), Error::kOk);
  EXPECT_FLOAT_EQ(status().az.target_deg, 10.0f);
  float deg = 350.0f;
  for (int t = 0; t < 1000 && (status().az.has_target || deg < 351.0f); ++t) {
    if (r.az.drive.cw()) deg += 0.06f;
    if (r.az.drive.ccw()) deg -= 0.06f;
    ma3_at(deg >= 360.0f ? deg - 360.0f : deg);
    r.now += 10;
    r.controller->tick(r.now);
  }
  EXPECT_NEAR(deg, 370.0f, 1.0f);                      // went CW through north
  EXPECT_NEAR(status().az.position_deg, 10.0f, 1.0f);  // reported as a compass angle
}

/// Starts `r` again on its MA3, which reads `reads_deg` (a 12-bit frame),
/// with the threshold input T1 as `beyond_360`.
void start_on_ma3(testing::FakeRotator& r, int reads_deg, bool beyond_360) {
  r.settings.set(Id::kAzSensor, 1);
  r.az.t1.on = beyond_360;
  const auto high = static_cast<std::uint32_t>(reads_deg * 4098 / 360 + 1);
  r.az.ma3.period = {high, 4097 - high, true};
  r.controller = std::make_unique<Controller>(r.settings, r.az.io(), r.el.io());
  r.controller->begin(0);
}

TEST(Ma3Axis, ANewZeroStaysOnTheTurnTheAxisIsOn) {
  // 0..450 rotator at 400 (MA3 reads 40, T1 on); re-zeroing by 5 deg leaves
  // it at 395, not at 35, and latches no jump fault.
  testing::FakeRotator r(false);
  start_on_ma3(r, 40, true);
  r.run_ms(50);
  ASSERT_NEAR(r.controller->status().az.position_deg, 400.0f, 0.2f);
  EXPECT_EQ(r.controller->status().az.raw_full_scale, 4096.0f);
  r.az.t1.on = false;  // only a start-up may consult it
  r.settings.set(Id::kAzMa3ZeroDeg, 5);
  r.run_ms(100);
  EXPECT_NEAR(r.controller->status().az.position_deg, 395.0f, 0.2f);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kNone);
}

TEST(Ma3Axis, ThresholdInputPicksTheOverlapTurnAtStartUp) {
  // An MA3 reads 30 deg; on a 0..450 rotator that is 30 or 390. T1 says "beyond 360".
  testing::FakeRotator r(false);
  start_on_ma3(r, 30, true);
  r.controller->tick(10);
  EXPECT_NEAR(r.controller->status().az.position_deg, 390.0f, 0.2f);

  start_on_ma3(r, 30, false);
  r.controller->tick(10);
  EXPECT_NEAR(r.controller->status().az.position_deg, 30.0f, 0.2f);
}

}  // namespace
}  // namespace rotord

namespace rotord {
namespace {

using settings::Id;

// park.after_idle_min: the rotator parks by itself once, after that many
// minutes without a command or motion; any command restarts the count.
class AutoParkTest : public ControllerTest {};

TEST_F(AutoParkTest, ParksOnceAfterTheIdleTimeAndEveryCommandRestartsIt) {
  r.settings.set(Id::kParkAzDeg, 180);
  r.settings.set(Id::kParkElDeg, 10);
  r.settings.set(Id::kParkAfterIdleMin, 2);
  ASSERT_EQ(r.controller->go_to(120.0f, 30.0f), Error::kOk);
  run_ms(30000);
  ASSERT_EQ(status().mode, Mode::kIdle);
  run_ms(60000);         // idle for well under two minutes since the motion ended
  r.controller->stop();  // a command: the count starts again
  run_ms(110000);
  EXPECT_EQ(status().mode, Mode::kIdle) << "parked before two idle minutes";
  EXPECT_NEAR(status().az.position_deg, 120.0f, 1.5f);
  run_ms(15000);
  EXPECT_EQ(status().mode, Mode::kPark);
  run_ms(60000);
  EXPECT_NEAR(status().az.position_deg, 180.0f, 1.5f);
  EXPECT_NEAR(status().el.position_deg, 10.0f, 1.5f);
  EXPECT_EQ(status().mode, Mode::kIdle);
  // Parked: not sent to park again while nothing happens.
  for (int i = 0; i < 40; ++i) {
    run_ms(10000);
    ASSERT_EQ(status().mode, Mode::kIdle) << "parked again after " << i * 10 << " s";
  }
}

TEST_F(AutoParkTest, ZeroNeverParks) {
  r.settings.set(Id::kParkAzDeg, 300);
  run_ms(3600000);
  EXPECT_EQ(status().mode, Mode::kIdle);
  EXPECT_NEAR(status().az.position_deg, 100.0f, 1.5f);
}

}  // namespace
}  // namespace rotord
