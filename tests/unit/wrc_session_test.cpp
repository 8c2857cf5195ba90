#include "protocol/wrc_session.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "fake_rotator.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using testing::StringSink;

class WrcTest : public ::testing::Test {
 protected:
  testing::FakeRotator r;
  WrcSession session{*r.controller, "9.9.9"};
  std::string ask(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    return sink.data;
  }
};

TEST_F(WrcTest, QueriesAndReplies) {
  r.run_ms(50);
  EXPECT_EQ(ask("AZ?\n"), "OK AZ 100.0\r\n");
  EXPECT_EQ(ask("EL?\n"), "OK EL 20.0\r\n");
  EXPECT_EQ(ask("STATE\n"), "OK STATE AZ=100.0 EL=20.0 SPEED=100 FLAGS=\r\n");
  EXPECT_EQ(ask("SPEED?\n"), "OK SPEED 100\r\n");
  EXPECT_EQ(ask("INFO\n"), "OK INFO rotord 9.9.9\r\n");
  EXPECT_EQ(ask("AZLIMITS?\n"), "OK AZLIMITS MIN=0 MAX=450\r\n");
  EXPECT_EQ(ask("AZOFFSET?\n"), "OK AZOFFSET 0.00\r\n");
  EXPECT_EQ(ask("FAULT?\n"), "OK FAULT AZ=NONE EL=NONE\r\n");
}

TEST_F(WrcTest, CommandsActOnTheController) {
  EXPECT_EQ(ask("AZ 200\n"), "OK AZ 200.00\r\n");
  EXPECT_TRUE(r.controller->status().az.has_target);
  EXPECT_FLOAT_EQ(r.controller->status().az.target_deg, 200.0f);
  EXPECT_EQ(ask("EL 45.5\r\n"), "OK EL 45.50\r\n");
  EXPECT_FLOAT_EQ(r.controller->status().el.target_deg, 45.5f);
  EXPECT_EQ(ask("STOP\n"), "OK STOP\r\n");
  EXPECT_FALSE(r.controller->status().az.has_target);
  EXPECT_EQ(ask("SPEED 80\n"), "OK SPEED 80.00\r\n");
  EXPECT_EQ(r.controller->status().speed_pct, 80);
  EXPECT_EQ(ask("MOVE cw\n"), "OK MOVE CW\r\n");
  EXPECT_TRUE(r.controller->status().az.jogging);
  r.run_ms(100);
  EXPECT_EQ(ask("STATE\n"), "OK STATE AZ=100.0 EL=20.0 SPEED=80 FLAGS=CW\r\n");
  EXPECT_EQ(ask("AZOFFSET -5.5\n"), "OK AZOFFSET -5.50\r\n");
  EXPECT_FLOAT_EQ(r.settings.f(settings::Id::kAzOffsetDeg), -5.5f);
  EXPECT_EQ(ask("PARK\n"), "OK PARK\r\n");
  EXPECT_EQ(r.controller->status().mode, Mode::kPark);
  EXPECT_EQ(ask("RESET\n"), "OK RESET\r\n");
  EXPECT_EQ(r.controller->status().speed_pct, 100);
}

TEST_F(WrcTest, AnOffsetFarBeyondTheJumpThresholdLatchesNoFault) {
  r.run_ms(50);
  ASSERT_LT(r.settings.f(settings::Id::kAzJumpDeg), 90.0f);
  EXPECT_EQ(ask("AZOFFSET 90\n"), "OK AZOFFSET 90.00\r\n");
  r.run_ms(200);
  EXPECT_EQ(ask("FAULT?\n"), "OK FAULT AZ=NONE EL=NONE\r\n");
  EXPECT_EQ(ask("AZ?\n"), "OK AZ 190.0\r\n");  // the position follows the offset
  r.az.set_deg(101.0f);                        // and the sensor
  r.run_ms(100);
  EXPECT_EQ(ask("AZ?\n"), "OK AZ 191.0\r\n");
  EXPECT_EQ(ask("AZOFFSET -90\n"), "OK AZOFFSET -90.00\r\n");  // 180 the other way
  r.run_ms(200);
  EXPECT_EQ(ask("FAULT?\n"), "OK FAULT AZ=NONE EL=NONE\r\n");
  EXPECT_EQ(ask("AZ?\n"), "OK AZ 11.0\r\n");
}

TEST_F(WrcTest, ErrorsChangeNothing) {
  const std::pair<const char*, const char*> kBad[] = {
      {"AZ abc\n", "ERROR INVALID AZIMUTH\r\n"},
      {"AZ 451\n", "ERROR INVALID AZIMUTH\r\n"},
      {"AZ -1\n", "ERROR INVALID AZIMUTH\r\n"},
      {"EL 200\n", "ERROR INVALID ELEVATION\r\n"},
      {"MOVE UPWARDS\n", "ERROR INVALID DIRECTION\r\n"},
      {"SPEED 0\n", "ERROR INVALID SPEED\r\n"},
      {"SPEED 5.5\n", "ERROR INVALID SPEED\r\n"},
      {"MONITOR 2\n", "ERROR INVALID ARGUMENT\r\n"},
      {"AZOFFSET 400\n", "ERROR INVALID AZIMUTH OFFSET\r\n"},
      {"FROB\n", "ERROR INVALID COMMAND\r\n"},
      {"AZ\n", "ERROR INVALID COMMAND\r\n"},
  };
  for (const auto& [line, reply] : kBad) EXPECT_EQ(ask(line), reply) << line;
  const RotatorStatus s = r.controller->status();
  EXPECT_FALSE(s.az.has_target);
  EXPECT_FALSE(s.el.has_target);
  EXPECT_EQ(s.speed_pct, 100);
  EXPECT_FLOAT_EQ(r.settings.f(settings::Id::kAzOffsetDeg), 0.0f);
}

TEST_F(WrcTest, LongLinesGetOneErrorAndTheSessionStaysUsable) {
  const std::string huge(1 << 20, 'A');
  EXPECT_EQ(ask(huge + "\n"), "ERROR COMMAND TOO LONG\r\n");
  EXPECT_EQ(ask("AZ?\n"), "OK AZ 100.0\r\n");
  // Binary garbage with NUL bytes is just an unknown command.
  EXPECT_EQ(ask(std::string("\x01\x00\xff\x8f", 4) + "\n"), "ERROR INVALID COMMAND\r\n");
  EXPECT_FALSE(r.controller->status().az.has_target);
}

TEST_F(WrcTest, AReadingAHairBelowZeroIsZeroNotMinusZero) {
  // Calibrated so that the antenna at its 0 deg end stop reads -0.03.
  ASSERT_EQ(r.settings.set(settings::Id::kAzOffsetDeg, -100.03).error, Error::kOk);
  ASSERT_EQ(r.settings.set(settings::Id::kElOffsetDeg, -20.04).error, Error::kOk);
  ASSERT_EQ(r.settings.set(settings::Id::kAzMinDeg, -90).error, Error::kOk);
  ASSERT_EQ(r.settings.set(settings::Id::kElMinDeg, -10).error, Error::kOk);
  r.run_ms(100);
  ASSERT_NEAR(r.controller->status().az.position_deg, -0.03f, 0.001f);
  EXPECT_EQ(ask("AZ?\n"), "OK AZ 0.0\r\n");
  EXPECT_EQ(ask("EL?\n"), "OK EL 0.0\r\n");
  EXPECT_EQ(ask("STATE\n").rfind("OK STATE AZ=0.0 EL=0.0 SPEED=", 0), 0u) << ask("STATE\n");
}

TEST_F(WrcTest, SplitAndPipelinedCommands) {
  EXPECT_EQ(ask("AZ"), "");
  EXPECT_EQ(ask("?"), "");
  EXPECT_EQ(ask("\r\nSPEED?\nAZ?\n\n"), "OK AZ 100.0\r\nOK SPEED 100\r\nOK AZ 100.0\r\n");
}

TEST_F(WrcTest, MonitorPushesStateTenTimesASecond) {
  EXPECT_EQ(ask("MONITOR 1\n"), "OK MONITOR 1\r\n");
  StringSink sink;
  for (Millis t = 10; t <= 1000; t += 10) {
    r.now = t;
    r.controller->tick(t);
    session.poll(t, sink);
  }
  EXPECT_EQ(sink.writes, 10);
  // Pushed as the WRC firmware pushes them: no "OK", unlike the reply to STATE.
  EXPECT_EQ(sink.data.rfind("STATE AZ=100.0 EL=20.0 SPEED=100 FLAGS=\r\nSTATE AZ=", 0), 0u)
      << sink.data;
  EXPECT_EQ(ask("STATE\n"), "OK STATE AZ=100.0 EL=20.0 SPEED=100 FLAGS=\r\n");
  EXPECT_EQ(ask("MONITOR 0\n"), "OK MONITOR 0\r\n");
  StringSink quiet;
  session.poll(5000, quiet);
  EXPECT_EQ(quiet.writes, 0);
}

TEST_F(WrcTest, MonitorKeepsTenASecondOfWallTimeWhateverTheSpeedup) {
  // rotord --speedup 10: the controller runs 100 ms per 10 ms of the
  // transport's (wall) clock; a monitoring client still gets 10 lines a second.
  StringSink first;
  session.poll(0, first);
  EXPECT_EQ(ask("MONITOR 1\n"), "OK MONITOR 1\r\n");
  StringSink sink;
  for (Millis wall = 10; wall <= 1000; wall += 10) {
    r.run_ms(100);
    session.poll(wall, sink);
  }
  EXPECT_EQ(sink.writes, 10);
}

}  // namespace
}  // namespace rotord::protocol
