#include "protocol/seed_session.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "fake_rotator.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using testing::StringSink;

class SeedTest : public ::testing::Test {
 protected:
  explicit SeedTest(bool with_el = true) : r(with_el) { r.run_ms(50); }
  testing::FakeRotator r;
  SeedSession session{*r.controller};
  std::string ask(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    return sink.data;
  }
  RotatorStatus status() const { return r.controller->status(); }
};

TEST_F(SeedTest, EnableRunDisable) {
  EXPECT_FALSE(session.enabled());
  EXPECT_EQ(ask("$E\n"), "$OK,E\r\n");
  EXPECT_TRUE(session.enabled());
  EXPECT_EQ(ask("$R,cw\n"), "$OK,R,CW\r\n");
  EXPECT_TRUE(status().az.jogging);
  r.run_ms(500);
  EXPECT_TRUE(r.az.drive.cw());
  EXPECT_EQ(ask("$Q\n"), "$Q,100.0,20.0,100,E,CW,STOP,NONE\r\n");
  EXPECT_EQ(ask("$D\r\n"), "$OK,D\r\n");
  EXPECT_FALSE(session.enabled());
  EXPECT_FALSE(status().az.jogging);
  r.run_ms(2000);
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_EQ(ask("$Q\n"), "$Q,100.0,20.0,100,D,STOP,STOP,NONE\r\n");
}

TEST_F(SeedTest, EveryDirectionAndCaseInsensitive) {
  ask("$e\n");
  EXPECT_EQ(ask("$r,CCW\n"), "$OK,R,CCW\r\n");
  r.run_ms(500);
  EXPECT_TRUE(r.az.drive.ccw());
  EXPECT_EQ(ask("$R,up\n"), "$OK,R,UP\r\n");
  r.run_ms(500);
  EXPECT_TRUE(r.el.drive.cw());
  EXPECT_EQ(ask("$D\n"), "$OK,D\r\n");
  r.run_ms(2000);
  EXPECT_EQ(ask("$E\n$R, down \n"), "$OK,E\r\n$OK,R,DOWN\r\n");
  r.run_ms(500);
  EXPECT_TRUE(r.el.drive.ccw());
  EXPECT_EQ(ask("$Q\n"), "$Q,100.0,20.0,100,E,STOP,DOWN,NONE\r\n");
}

TEST_F(SeedTest, SpeedSetsTheControllerSpeed) {
  EXPECT_EQ(ask("$S,40\n"), "$OK,S,40\r\n");
  EXPECT_EQ(status().speed_pct, 40);
  EXPECT_EQ(ask("$S,100\n"), "$OK,S,100\r\n");
  EXPECT_EQ(ask("$S,1\n"), "$OK,S,1\r\n");
  EXPECT_EQ(status().speed_pct, 1);
}

TEST_F(SeedTest, RunWhileDisabledIsRefusedAndNothingMoves) {
  EXPECT_EQ(ask("$R,cw\n"), "$ERR,DISABLED\r\n");
  ask("$E\n");
  ask("$D\n");
  EXPECT_EQ(ask("$R,ccw\n"), "$ERR,DISABLED\r\n");
  r.run_ms(500);
  EXPECT_FALSE(status().az.jogging);
  EXPECT_FALSE(r.az.drive.cw() || r.az.drive.ccw());
}

TEST_F(SeedTest, BadInputGetsErrorsAndChangesNothing) {
  ask("$E\n");
  // Each malformed line and the error it gets, one at a time.
  const std::pair<const char*, const char*> kBad[] = {
      {"E\n", "$ERR,SYNTAX\r\n"},       {"$\n", "$ERR,UNKNOWN\r\n"},
      {"$X\n", "$ERR,UNKNOWN\r\n"},     {"$X,1,2,3\n", "$ERR,SYNTAX\r\n"},
      {"$E,1\n", "$ERR,SYNTAX\r\n"},    {"$D,now\n", "$ERR,SYNTAX\r\n"},
      {"$Q,1\n", "$ERR,SYNTAX\r\n"},    {"$S\n", "$ERR,SYNTAX\r\n"},
      {"$S,\n", "$ERR,SYNTAX\r\n"},     {"$S,fast\n", "$ERR,SYNTAX\r\n"},
      {"$S,50.5\n", "$ERR,SYNTAX\r\n"}, {"$S,0\n", "$ERR,RANGE\r\n"},
      {"$S,101\n", "$ERR,RANGE\r\n"},   {"$S,-5\n", "$ERR,RANGE\r\n"},
      {"$S,50,1\n", "$ERR,SYNTAX\r\n"}, {"$R\n", "$ERR,SYNTAX\r\n"},
      {"$R,left\n", "$ERR,SYNTAX\r\n"}, {"$R,cw,fast\n", "$ERR,SYNTAX\r\n"},
  };
  for (const auto& [line, reply] : kBad) EXPECT_EQ(ask(line), reply) << line;
  EXPECT_EQ(ask(std::string("$\0\xff", 3) + "\n"), "$ERR,UNKNOWN\r\n");
  EXPECT_EQ(ask(std::string(500, '$') + "\n$Q\n"),
            "$ERR,TOOLONG\r\n$Q,100.0,20.0,100,E,STOP,STOP,NONE\r\n");
  EXPECT_EQ(ask("\n\r\n  \n"), "");
  EXPECT_EQ(status().speed_pct, 100);
  EXPECT_FALSE(status().az.jogging || status().el.jogging);
}

TEST_F(SeedTest, LimitsAndFaultsAreReported) {
  ask("$E\n");
  // Driven with the pot standing still: the axis stalls and latches a fault.
  ask("$R,cw\n");
  r.run_ms(5000);
  EXPECT_EQ(ask("$Q\n"), "$Q,100.0,20.0,100,E,STOP,STOP,STALL\r\n");
  EXPECT_EQ(ask("$R,cw\n"), "$ERR,FAULT\r\n");
  r.controller->reset();
  for (float deg = 100; deg <= 450; deg += 0.4f) {  // slowly, a jump would be a fault
    r.az.set_deg(deg);
    r.run_ms(10);
  }
  r.az.set_deg(450);
  r.run_ms(300);
  EXPECT_EQ(ask("$R,cw\n"), "$ERR,LIMIT\r\n");
}

class SeedAzOnlyTest : public SeedTest {
 protected:
  SeedAzOnlyTest() : SeedTest(false) {}
};

TEST_F(SeedAzOnlyTest, ElevationIsUnsupported) {
  ask("$E\n");
  EXPECT_EQ(ask("$R,up\n"), "$ERR,UNSUPPORTED\r\n");
  EXPECT_EQ(ask("$Q\n"), "$Q,100.0,0.0,100,E,STOP,STOP,NONE\r\n");
}

}  // namespace
}  // namespace rotord::protocol
