#include "protocol/gs232_session.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fake_rotator.hpp"
#include "protocol/gs232_angles.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

using testing::StringSink;

constexpr const char* kErr = "?>\r\n";

/// A G-5500-like fake: az 0..450 at 100 deg, el 0..180 at 20 deg.
class Gs232Test : public ::testing::Test {
 protected:
  explicit Gs232Test(bool with_el = true) : r(with_el) {
    // The fake has no motor: the pot only moves when a test turns it, so a
    // commanded axis must not stall out while a test waits for a list step.
    r.settings.set(Id::kAzStallMs, 60000);
    r.settings.set(Id::kElStallMs, 60000);
    r.run_ms(50);
  }

  std::string ask(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    last_writes = sink.writes;
    return sink.data;
  }
  void variant(char v) { r.settings.set(Id::kGs232Variant, v == 'A' ? 0 : 1); }
  const AxisStatus az() { return r.controller->status().az; }
  const AxisStatus el() { return r.controller->status().el; }
  void expect_still() {
    EXPECT_FALSE(az().has_target);
    EXPECT_FALSE(az().jogging);
    EXPECT_FALSE(el().has_target);
    EXPECT_FALSE(el().jogging);
  }
  /// Turns the pot by hand, one degree per tick (a jump would be rejected as
  /// implausible).
  void slide(testing::FakeAxisHardware& axis, float from_deg, float to_deg) {
    const float step = to_deg > from_deg ? 1.0f : -1.0f;
    for (float deg = from_deg; std::fabs(deg - to_deg) >= 1.0f; deg += step) {
      axis.set_deg(deg);
      r.run_ms(10);
    }
    axis.set_deg(to_deg);
    r.run_ms(100);
  }
  /// Advances the controller and lets the session step its timed list.
  void run_ms(Millis ms) {
    StringSink sink;
    for (Millis t = 0; t < ms; t += 10) {
      r.run_ms(10);
      session.poll(r.now, sink);
    }
    EXPECT_EQ(sink.data, "");  // stepping is silent
  }

  testing::FakeRotator r;
  Gs232Session session{*r.controller};
  int last_writes = 0;
};

class Gs232AzOnlyTest : public Gs232Test {
 protected:
  Gs232AzOnlyTest() : Gs232Test(false) {}
};

// --- reports ------------------------------------------------------------------

TEST_F(Gs232Test, GS232BReportsAzEqualsAndElEquals) {
  variant('B');
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
  EXPECT_EQ(ask("B\r"), "EL=020\r\n");
  EXPECT_EQ(ask("C2\r"), "AZ=100  EL=020\r\n");
  EXPECT_EQ(last_writes, 1);  // one write per reply: Gpredict-style readers need it whole
}

TEST_F(Gs232Test, GS232AReportsPlusZeroFields) {
  variant('A');
  EXPECT_EQ(ask("C\r"), "+0100\r\n");
  EXPECT_EQ(ask("B\r"), "+0020\r\n");
  EXPECT_EQ(ask("C2\r"), "+0100+0020\r\n");
  EXPECT_EQ(last_writes, 1);
}

TEST_F(Gs232Test, LowerCaseSpacesAndEveryLineEndWork) {
  variant('A');
  for (const char* spelling : {"c2\r", "C 2\r", "C2\n", "C2\r\n", "  C2  \r"})
    EXPECT_EQ(ask(spelling), "+0100+0020\r\n") << spelling;
}

TEST_F(Gs232Test, SplitAndCoalescedCommands) {
  variant('A');
  EXPECT_EQ(ask("C"), "");
  EXPECT_EQ(ask("2"), "");
  EXPECT_EQ(ask("\r"), "+0100+0020\r\n");
  // Hamlib 602 writes back to back: one segment, one reply per command.
  EXPECT_EQ(ask("W200 030\rS\rC2\r"), "\r\r+0100+0020\r\n");
}

TEST_F(Gs232Test, EmptyCommandsAreIgnoredLikeHamlib603sExtraCr) {
  variant('B');
  EXPECT_EQ(ask("\r\r\n\n\r"), "");
  EXPECT_EQ(ask("W010 020\r"), "\r");
  EXPECT_EQ(ask("\r"), "");
  EXPECT_EQ(ask("X4\r\rR\r\r"), "\r\r");
}

TEST_F(Gs232Test, WithoutAcknowledgementsOnlyDataAndErrorsAreSent) {
  // Hamlib 602 writes W and then C2 at once and would read a CR as the reply.
  variant('A');
  r.settings.set(Id::kGs232AckWrites, 0);
  EXPECT_EQ(ask("W200 030\rS\rX2\rR\rA\rC2\r"), "+0100+0020\r\n");
  EXPECT_EQ(ask("W999 000\r"), kErr);
  EXPECT_EQ(ask("M001 100 200\rT\rN\r"), "+0001+0002\r\n");
}

TEST(Gs232Angles, ReportsOnTheScaleOrAsCompassBearing) {
  using gs232::AzRange;
  using gs232::report_az_deg;
  EXPECT_EQ(report_az_deg(400.0f, AzRange::k450, false), 400);
  EXPECT_EQ(report_az_deg(450.4f, AzRange::k450, false), 450);
  EXPECT_EQ(report_az_deg(400.0f, AzRange::k360, false), 40);
  EXPECT_EQ(report_az_deg(360.0f, AzRange::k360, false), 360);
  EXPECT_EQ(report_az_deg(-10.0f, AzRange::k360, false), 350);
  EXPECT_EQ(report_az_deg(-180.0f, AzRange::k360, false), 180);
  EXPECT_EQ(report_az_deg(-0.4f, AzRange::k450, false), 0);
  EXPECT_EQ(report_az_deg(500.0f, AzRange::k450, false), 140);
  EXPECT_EQ(report_az_deg(359.6f, AzRange::k360, true), 0);
  EXPECT_EQ(report_az_deg(123.4f, AzRange::k360, true), 123);
  EXPECT_EQ(report_az_deg(NAN, AzRange::k360, false), 0);
  EXPECT_EQ(report_az_deg(1e30f, AzRange::k450, false), 100000 % 360);
  EXPECT_EQ(gs232::report_el_deg(-5.0f), 0);
  EXPECT_EQ(gs232::report_el_deg(185.0f), 180);
  EXPECT_EQ(gs232::report_el_deg(44.5f), 45);
}

TEST(Gs232Angles, TargetsAreUnwrappedInsideTheTravelElseCompass) {
  Limits g5500;
  g5500.az_min_deg = 0;
  g5500.az_max_deg = 450;
  auto goal = gs232::az_goal(10, g5500);
  EXPECT_EQ(goal.mode, AzTarget::kUnwrapped);
  EXPECT_FLOAT_EQ(goal.az_deg, 10.0f);
  goal = gs232::az_goal(450, g5500);
  EXPECT_EQ(goal.mode, AzTarget::kUnwrapped);
  EXPECT_FLOAT_EQ(goal.az_deg, 450.0f);

  Limits south_stop;
  south_stop.az_min_deg = -180;
  south_stop.az_max_deg = 180;
  goal = gs232::az_goal(350, south_stop);
  EXPECT_EQ(goal.mode, AzTarget::kCompass);
  EXPECT_FLOAT_EQ(goal.az_deg, 350.0f);

  Limits plain;  // 0..360
  goal = gs232::az_goal(400, plain);
  EXPECT_EQ(goal.mode, AzTarget::kCompass);
  EXPECT_FLOAT_EQ(goal.az_deg, 40.0f);

  Limits endless;
  endless.az_continuous = true;
  goal = gs232::az_goal(360, endless);
  EXPECT_EQ(goal.mode, AzTarget::kCompass);
  EXPECT_FLOAT_EQ(goal.az_deg, 0.0f);
}

TEST(Gs232Angles, AutoRangeFollowsTheTravel) {
  settings::Settings s;
  Limits l;
  l.az_max_deg = 450;
  EXPECT_EQ(gs232::az_range(s, l), gs232::AzRange::k450);
  l.az_max_deg = 360;
  EXPECT_EQ(gs232::az_range(s, l), gs232::AzRange::k360);
  l.az_max_deg = 450;
  l.az_continuous = true;
  EXPECT_EQ(gs232::az_range(s, l), gs232::AzRange::k360);
  s.set(Id::kGs232AzRange, 2);
  EXPECT_EQ(gs232::az_range(s, l), gs232::AzRange::k450);
  s.set(Id::kGs232AzRange, 1);
  l.az_continuous = false;
  EXPECT_EQ(gs232::az_range(s, l), gs232::AzRange::k360);
}

TEST_F(Gs232Test, ReportsInTheOverlapOnBothScales) {
  variant('B');
  slide(r.az, 100, 400);
  ASSERT_NEAR(az().position_deg, 400.0f, 0.5f);
  EXPECT_EQ(ask("C\r"), "AZ=400\r\n");
  EXPECT_EQ(ask("P36\r"), "\r");
  EXPECT_EQ(ask("C\r"), "AZ=040\r\n");
}

// --- go to --------------------------------------------------------------------

TEST_F(Gs232Test, WTurnsBothAxesAndMTurnsAzimuth) {
  EXPECT_EQ(ask("W200 045\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 200.0f);
  EXPECT_FLOAT_EQ(el().target_deg, 45.0f);
  EXPECT_EQ(ask("M350\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 350.0f);
  EXPECT_FLOAT_EQ(el().target_deg, 45.0f);
  EXPECT_EQ(ask("M 5\r"), "\r");  // fewer than three digits and a space are accepted
  EXPECT_FLOAT_EQ(az().target_deg, 5.0f);
}

TEST_F(Gs232Test, OverlapAnglesOnThe450ScaleAreUnwrappedPositions) {
  EXPECT_EQ(ask("W400 170\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 400.0f);
  EXPECT_FLOAT_EQ(el().target_deg, 170.0f);
  EXPECT_EQ(ask("W450 180\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 450.0f);
  // M010 from 100 turns to 10, not to 370: the real controller's scale.
  EXPECT_EQ(ask("M010\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 10.0f);
}

TEST_F(Gs232Test, The360ScaleRefusesOverlapAngles) {
  variant('B');
  EXPECT_EQ(ask("P36\r"), "\r");
  EXPECT_EQ(ask("W400 010\r"), kErr);
  EXPECT_EQ(ask("M361\r"), kErr);
  expect_still();
  EXPECT_EQ(ask("M360\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 360.0f);
  EXPECT_EQ(ask("P45\r"), "\r");
  EXPECT_EQ(r.settings.i(Id::kGs232AzRange), 2);
  EXPECT_EQ(ask("M450\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 450.0f);
}

TEST_F(Gs232Test, AnglesOutsideTheTravelAreCompassBearingsInsideIt) {
  // A south-stop rotator, -180..180, told 350 (Hamlib sends -10 as 350).
  r.settings.set(Id::kAzMinDeg, -180);
  r.settings.set(Id::kAzMaxDeg, 180);
  r.run_ms(20);
  EXPECT_EQ(ask("W350 000\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, -10.0f);
  EXPECT_EQ(ask("M180\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 180.0f);
  // A 0..360 rotator told 400 on the 450 scale goes to 40, never past 360.
  r.settings.set(Id::kAzMinDeg, 0);
  r.settings.set(Id::kAzMaxDeg, 360);
  r.settings.set(Id::kGs232AzRange, 2);
  r.run_ms(20);
  EXPECT_EQ(ask("M400\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 40.0f);
}

TEST_F(Gs232Test, BadTargetsAnswerTheErrorPromptAndMoveNothing) {
  for (const char* bad : {"W451 000\r", "W100 181\r", "M451\r", "M-10\r", "M10.5\r", "M1000\r",
                          "Mabc\r", "W100\r", "W100 010 020 030\r", "M\r", "W\r", "M002 100\r",
                          "W-10 010\r", "W010 -01\r", "M+10\r", "W0100 010\r", "M 1 2 x\r"}) {
    EXPECT_EQ(ask(bad), kErr) << bad;
  }
  expect_still();
}

TEST_F(Gs232Test, ElevationBeyondTheAxisLimitMovesNeitherAxis) {
  r.settings.set(Id::kElMaxDeg, 90);
  r.run_ms(20);
  EXPECT_EQ(ask("W200 170\r"), kErr);
  expect_still();
}

TEST_F(Gs232Test, AFaultedRotatorRefusesToMove) {
  r.az.adc.counts = 0;  // wiper at the rail: a sensor fault latches
  r.run_ms(2000);
  ASSERT_NE(az().fault, AxisFault::kNone);
  EXPECT_EQ(ask("M200\r"), kErr);
  EXPECT_EQ(ask("R\r"), kErr);
  EXPECT_EQ(ask("S\r"), "\r");
}

TEST_F(Gs232AzOnlyTest, AzimuthOnlyRotatorIgnoresTheElevationFieldAndRefusesElevationCommands) {
  variant('A');
  EXPECT_EQ(ask("C2\r"), "+0100+0000\r\n");
  EXPECT_EQ(ask("B\r"), "+0000\r\n");
  EXPECT_EQ(ask("W010 000\r"), "\r");  // Hamlib 611
  EXPECT_FLOAT_EQ(az().target_deg, 10.0f);
  for (const char* bad : {"U\r", "D\r", "E\r", "O2\r", "F2\r"}) EXPECT_EQ(ask(bad), kErr) << bad;
}

// --- manual moves, stops, speed ----------------------------------------------------

TEST_F(Gs232Test, ManualTurnsAndStops) {
  EXPECT_EQ(ask("R\r"), "\r");
  EXPECT_TRUE(az().jogging);
  EXPECT_EQ(ask("U\r"), "\r");
  EXPECT_TRUE(el().jogging);
  r.run_ms(100);
  EXPECT_EQ(az().drive_dir, Direction::kCw);
  EXPECT_EQ(el().drive_dir, Direction::kCw);
  EXPECT_EQ(ask("A\r"), "\r");
  EXPECT_FALSE(az().jogging);
  EXPECT_TRUE(el().jogging);
  EXPECT_EQ(ask("E\r"), "\r");
  EXPECT_FALSE(el().jogging);
  EXPECT_EQ(ask("L\r"), "\r");
  EXPECT_TRUE(az().jogging);
  EXPECT_EQ(ask("D\r"), "\r");
  EXPECT_TRUE(el().jogging);
  EXPECT_EQ(ask("S\r"), "\r");
  expect_still();
  EXPECT_EQ(ask("W300 060\r"), "\r");
  EXPECT_EQ(ask("S\r"), "\r");
  expect_still();
}

TEST_F(Gs232Test, SpeedsX1ToX4) {
  const int expected[] = {25, 50, 75, 100};
  for (int n = 1; n <= 4; ++n) {
    EXPECT_EQ(ask("X" + std::to_string(n) + "\r"), "\r");
    EXPECT_EQ(r.controller->status().speed_pct, expected[n - 1]);
  }
  for (const char* bad : {"X0\r", "X5\r", "X\r", "X12\r", "Xa\r"}) EXPECT_EQ(ask(bad), kErr) << bad;
  EXPECT_EQ(r.controller->status().speed_pct, 100);
  EXPECT_EQ(ask("R\r"), "\r");
  EXPECT_EQ(ask("x1\r"), "\r");  // while turning
  EXPECT_EQ(r.controller->status().speed_pct, 25);
  EXPECT_TRUE(az().jogging);
}

// --- timed lists --------------------------------------------------------------

TEST_F(Gs232Test, TimedAzimuthListStepsEveryInterval) {
  // Each step's target to the degree: the lead rule (which sends a steady
  // stream's axes up to a band ahead) is off here.
  r.settings.set(Id::kTrackStreamLead, 0);
  EXPECT_EQ(ask("N\r"), kErr);  // nothing stored
  EXPECT_EQ(ask("T\r"), kErr);
  EXPECT_EQ(ask("M002 150 200 250\r"), "\r");
  EXPECT_EQ(session.list_size(), 3u);
  EXPECT_FLOAT_EQ(az().target_deg, 150.0f);  // turns to the first point at once
  EXPECT_EQ(ask("N\r"), "+0001+0003\r\n");
  run_ms(5000);
  EXPECT_FLOAT_EQ(az().target_deg, 150.0f);  // and waits for T
  EXPECT_EQ(ask("T\r"), "\r");
  EXPECT_TRUE(session.list_running());
  run_ms(1990);
  EXPECT_FLOAT_EQ(az().target_deg, 150.0f);
  EXPECT_EQ(ask("N\r"), "+0001+0003\r\n");
  run_ms(20);
  EXPECT_FLOAT_EQ(az().target_deg, 200.0f);
  EXPECT_EQ(ask("N\r"), "+0002+0003\r\n");
  run_ms(2000);
  EXPECT_FLOAT_EQ(az().target_deg, 250.0f);
  EXPECT_EQ(ask("N\r"), "+0003+0003\r\n");
  run_ms(2000);
  EXPECT_FALSE(session.list_running());
  EXPECT_EQ(ask("N\r"), "+0003+0003\r\n");
  // The list stays stored: T runs it again.
  EXPECT_EQ(ask("T\r"), "\r");
  EXPECT_FLOAT_EQ(az().target_deg, 150.0f);
  EXPECT_EQ(ask("N\r"), "+0001+0003\r\n");
}

TEST_F(Gs232Test, TimedAzElListAndStopKeepsItStored) {
  EXPECT_EQ(ask("W001 100 010 200 020 300 030\r"), "\r");
  EXPECT_EQ(session.list_size(), 3u);
  EXPECT_FLOAT_EQ(el().target_deg, 10.0f);
  EXPECT_EQ(ask("T\r"), "\r");
  run_ms(1000);
  EXPECT_FLOAT_EQ(az().target_deg, 200.0f);
  EXPECT_FLOAT_EQ(el().target_deg, 20.0f);
  EXPECT_EQ(ask("S\r"), "\r");
  EXPECT_FALSE(session.list_running());
  expect_still();
  run_ms(3000);
  expect_still();  // no more steps after S
  EXPECT_EQ(ask("N\r"), "+0002+0003\r\n");
  EXPECT_EQ(session.list_size(), 3u);
}

TEST_F(Gs232Test, ManualCommandsEndTheStepping) {
  EXPECT_EQ(ask("M001 150 200\r"), "\r");
  EXPECT_EQ(ask("T\r"), "\r");
  EXPECT_EQ(ask("L\r"), "\r");
  EXPECT_FALSE(session.list_running());
  run_ms(2000);
  EXPECT_TRUE(az().jogging);  // no step took over the manual turn
}

TEST_F(Gs232Test, AnyMOrWClearsTheListAndBadListsAreRefused) {
  EXPECT_EQ(ask("M010 150 200\r"), "\r");
  EXPECT_EQ(ask("M\r"), kErr);  // the manual: error prompt, memories cleared
  EXPECT_EQ(session.list_size(), 0u);
  EXPECT_EQ(ask("N\r"), kErr);
  EXPECT_EQ(ask("M010 150 200\r"), "\r");
  EXPECT_EQ(ask("W100 010\r"), "\r");
  EXPECT_EQ(session.list_size(), 0u);
  for (const char* bad : {"M000 150 200\r", "M1000 150 200\r", "M010 150 451\r",
                          "W010 100 010 200\r", "W010 100 181 200 010\r"}) {
    EXPECT_EQ(ask(bad), kErr) << bad;
    EXPECT_EQ(session.list_size(), 0u) << bad;
  }
}

TEST_F(Gs232Test, ListsUpToTheCapacityAndNoMore) {
  std::string full = "M001";
  for (std::size_t n = 0; n < Gs232Session::kMaxListPoints; ++n)
    full += " 1" + std::to_string(n % 90);
  EXPECT_EQ(ask(full + "\r"), "\r");
  EXPECT_EQ(session.list_size(), Gs232Session::kMaxListPoints);
  EXPECT_EQ(ask(full + " 100\r"), kErr);
  EXPECT_EQ(session.list_size(), 0u);
  std::string pairs = "W001";
  for (std::size_t n = 0; n < Gs232Session::kMaxListPoints; ++n) pairs += " 100 010";
  EXPECT_EQ(ask(pairs + "\r"), "\r");
  EXPECT_EQ(session.list_size(), Gs232Session::kMaxListPoints);
  EXPECT_EQ(ask(pairs + " 100 010\r"), kErr);
}

TEST_F(Gs232Test, AnOverlongLineIsOneErrorAndTheSessionStaysUsable) {
  variant('A');
  EXPECT_EQ(ask(std::string(100000, '1') + "\r"), kErr);
  EXPECT_EQ(ask(std::string(Gs232Session::kMaxLineLength + 1, ' ') + "\r"), kErr);
  EXPECT_EQ(ask("C2\r"), "+0100+0020\r\n");
  expect_still();
}

// --- calibration --------------------------------------------------------------

TEST_F(Gs232Test, GS232AOffsetAndFullScaleStoreThePotCalibration) {
  variant('A');
  const float raw = az().raw;  // 1000 counts at 100 deg
  EXPECT_EQ(ask("O\r"), "+0000\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzPotCalLoCounts), raw);
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzPotCalLoDeg), 0.0f);  // az.min_deg: the CCW stop
  slide(r.az, 100, 110);
  const float raw_hi = az().raw;
  EXPECT_EQ(ask("F\r"), "+0450\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzPotCalHiCounts), raw_hi);
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzPotCalHiDeg), 450.0f);  // az.max_deg: the CW stop

  const float el_raw = el().raw;
  EXPECT_EQ(ask("F2\r"), "+0" + std::string(ask("C\r").substr(2, 3)) + "+0180\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kElPotCalHiCounts), el_raw);
  EXPECT_FLOAT_EQ(r.settings.f(Id::kElPotCalHiDeg), 180.0f);
}

TEST_F(Gs232Test, OffsetCalibrationFarFromTheReadingLatchesNoFault) {
  // At 100 deg, "this is the CCW stop": the reading moves 100 deg in one step,
  // far beyond az.jump_deg. The axis follows the new calibration instead of
  // latching sensor_jump, and still turns.
  variant('A');
  ASSERT_LT(r.settings.f(Id::kAzJumpDeg), 100.0f);
  EXPECT_EQ(ask("O\r"), "+0000\r\n");
  r.run_ms(200);
  EXPECT_EQ(az().fault, AxisFault::kNone);
  EXPECT_NEAR(az().position_deg, 0.0f, 0.5f);
  EXPECT_EQ(ask("C\r"), "+0000\r\n");
  EXPECT_EQ(ask("M010\r"), "\r");
  EXPECT_TRUE(az().has_target);
  EXPECT_EQ(ask("S\r"), "\r");
}

TEST_F(Gs232Test, CalibrationSubtractsTheAxisOffset) {
  variant('A');
  r.settings.set(Id::kElOffsetDeg, 2.0);
  r.run_ms(20);
  EXPECT_EQ(ask("O2\r").substr(5), "+0000\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kElPotCalLoDeg), -2.0f);  // + 2 offset = 0 at the stop
}

TEST_F(Gs232Test, CalibrationThatBreaksAConsistencyRuleChangesNothing) {
  variant('A');
  r.settings.set(Id::kAzPotCalHiCounts, az().raw);
  const double lo_counts = r.settings.get(Id::kAzPotCalLoCounts);
  const double lo_deg = r.settings.get(Id::kAzPotCalLoDeg);
  EXPECT_EQ(ask("O\r"), kErr);  // both points at the same counts
  EXPECT_EQ(r.settings.get(Id::kAzPotCalLoCounts), lo_counts);
  EXPECT_EQ(r.settings.get(Id::kAzPotCalLoDeg), lo_deg);
}

TEST_F(Gs232Test, GS232BOffsetCalibrationAsksFirst) {
  variant('B');
  const double before = r.settings.get(Id::kAzPotCalLoCounts);
  EXPECT_EQ(ask("O\r"), "are you sure?\r\n");
  EXPECT_EQ(ask("\r"), "");  // still waiting
  EXPECT_EQ(ask("n\r"), "\r");
  EXPECT_EQ(r.settings.get(Id::kAzPotCalLoCounts), before);
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");  // back to commands
  // Another command instead of an answer is that command, and cancels.
  EXPECT_EQ(ask("R\r"), "\r");
  EXPECT_EQ(ask("O\r"), "are you sure?\r\n");
  EXPECT_EQ(ask("S\r"), "\r");
  expect_still();
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
  EXPECT_EQ(r.settings.get(Id::kAzPotCalLoCounts), before);
  EXPECT_EQ(ask("O\r"), "are you sure?\r\n");
  EXPECT_EQ(ask("y\r"), "Completed\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzPotCalLoCounts), az().raw);
  EXPECT_EQ(ask("O2\r"), "are you sure?\r\n");
  EXPECT_EQ(ask("Y\r"), "Completed\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kElPotCalLoCounts), el().raw);
  EXPECT_FLOAT_EQ(r.settings.f(Id::kElPotCalLoDeg), 0.0f);
  slide(r.az, 100, 120);
  EXPECT_EQ(ask("F\r"), "AZ=450\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzPotCalHiDeg), 450.0f);
}

TEST_F(Gs232Test, Ma3OffsetCalibrationSetsTheZeroAndHasNoFullScale) {
  variant('A');
  r.settings.set(Id::kAzSensor, 1);
  r.settings.set(Id::kAzMa3Bits, 1);                // 12 bit
  r.az.ma3.period = {1024 + 1, 4097 - 1025, true};  // code 1023 = 89.9 deg
  r.run_ms(100);
  ASSERT_EQ(az().fault, AxisFault::kNone);
  EXPECT_EQ(ask("O\r"), "+0000\r\n");
  EXPECT_NEAR(r.settings.f(Id::kAzMa3ZeroDeg), az().raw * 360.0f / 4096.0f, 0.01f);
  EXPECT_EQ(ask("F\r"), kErr);
}

TEST_F(Gs232Test, CalibrationNeedsAWorkingSensor) {
  variant('A');
  r.el.adc.counts = 0;
  r.run_ms(2000);
  ASSERT_EQ(el().fault, AxisFault::kSensorRange);
  const double before = r.settings.get(Id::kElPotCalLoCounts);
  EXPECT_EQ(ask("O2\r"), kErr);
  EXPECT_EQ(r.settings.get(Id::kElPotCalLoCounts), before);
}

// --- variant-specific and unknown commands -------------------------------------------

TEST_F(Gs232Test, HelpPages) {
  variant('A');
  EXPECT_EQ(ask("H\r").rfind("---------- COMMAND LIST 1", 0), 0u);
  EXPECT_EQ(ask("H2\r").rfind("---------- COMMAND LIST 2", 0), 0u);
  EXPECT_EQ(ask("H3\r"), kErr);  // the GS-232B's page
  variant('B');
  const std::string h3 = ask("H3\r");
  EXPECT_EQ(h3.rfind("---------- COMMAND LIST 3", 0), 0u);
  EXPECT_NE(h3.find("mode 450 Degree\r\nN Center\r\n"), std::string::npos) << h3;
}

TEST_F(Gs232Test, ZTogglesTheCentreOnlyOnThe360Scale) {
  variant('B');
  EXPECT_EQ(ask("Z\r"), "\r");  // 450 mode: ignored
  EXPECT_NE(ask("H3\r").find("N Center"), std::string::npos);
  EXPECT_EQ(ask("P36\r"), "\r");
  EXPECT_EQ(ask("Z\r"), "\r");
  EXPECT_NE(ask("H3\r").find("mode 360 Degree\r\nS Center"), std::string::npos);
  EXPECT_EQ(ask("Z\r"), "\r");
  EXPECT_NE(ask("H3\r").find("N Center"), std::string::npos);
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");  // angles stay compass bearings either way
}

TEST_F(Gs232Test, GS232BOnlyCommandsAreErrorsOnTheA) {
  variant('A');
  for (const char* bad : {"P36\r", "P45\r", "Z\r"}) EXPECT_EQ(ask(bad), kErr) << bad;
  EXPECT_EQ(r.settings.i(Id::kGs232AzRange), 0);
}

TEST_F(Gs232Test, UnknownCommandsAndGarbage) {
  variant('B');
  for (const char* bad :
       {"Q\r", "C3\r", "CC\r", "C22\r", "B2\r", "R1\r", "S1\r", "T1\r", "N1\r", "O3\r", "F1\r",
        "H4\r", "P37\r", "P\r", "Z1\r", "AZ\r", "?\r", "1\r", "CCCCCC\r"}) {
    EXPECT_EQ(ask(bad), kErr) << bad;
  }
  EXPECT_EQ(ask(std::string("\0\xff\x01\x7f\r", 5)), kErr);
  expect_still();
  EXPECT_EQ(ask("C2\r"), "AZ=100  EL=020\r\n");
}

TEST_F(Gs232Test, VariantChangesTakeEffectAtOnce) {
  variant('A');
  EXPECT_EQ(ask("C\r"), "+0100\r\n");
  variant('B');
  EXPECT_EQ(ask("C\r"), "AZ=100\r\n");
}

}  // namespace
}  // namespace rotord::protocol
