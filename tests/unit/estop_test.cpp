// The emergency-stop input (issue 12): active, both axes stop at once and
// latch ESTOP; nothing moves and RESET is refused until it is released.
#include <gtest/gtest.h>

#include "fake_rotator.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/wrc_session.hpp"
#include "string_sink.hpp"

namespace rotord {
namespace {

using settings::Id;

class Estop : public ::testing::Test {
 protected:
  void SetUp() override {
    estop.on = true;  // a normally-closed contact, released: closed
    r.controller->attach_estop(&estop);
    r.run_ms(20);
  }
  std::string ask_wrc(const std::string& line) {
    testing::StringSink sink;
    wrc.receive(line, sink);
    return sink.data;
  }
  testing::FakeRotator r;
  testing::FakeSwitch estop;
  protocol::WrcSession wrc{*r.controller, "9"};
};

TEST_F(Estop, PressedItStopsBothAxesAtOnceAndLatches) {
  ASSERT_EQ(r.controller->go_to(300.0f, 60.0f), Error::kOk);
  r.run_ms(300);
  ASSERT_TRUE(r.az.drive.cw());
  estop.on = false;  // pressed: the contact opens
  r.run_ms(10);      // the first tick
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_FALSE(r.el.drive.cw());
  EXPECT_TRUE(r.controller->estop_active());
  const RotatorStatus s = r.controller->status();
  EXPECT_EQ(s.az.fault, AxisFault::kEstop);
  EXPECT_EQ(s.el.fault, AxisFault::kEstop);
  EXPECT_STREQ(axis_fault_name(s.az.fault), "ESTOP");
  EXPECT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kFaulted);
  EXPECT_NE(r.controller->move(AxisId::kAz, Direction::kCw), Error::kOk);
  EXPECT_EQ(ask_wrc("RESET\n"), "ERROR ESTOP\r\n");
  EXPECT_EQ(r.controller->reset(), Error::kFaulted);
  r.run_ms(100);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kEstop);

  // Released, it stays latched until RESET.
  estop.on = true;
  r.run_ms(100);
  EXPECT_FALSE(r.controller->estop_active());
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kEstop);
  EXPECT_EQ(ask_wrc("RESET\n"), "OK RESET\r\n");
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kNone);
  EXPECT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
}

TEST_F(Estop, ABrokenWireOfANormallyClosedContactStops) {
  estop.on = false;  // open circuit
  r.run_ms(10);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kEstop);
}

TEST_F(Estop, ANormallyOpenContactStopsWhenClosed) {
  ASSERT_EQ(r.settings.set(Id::kEstopNormallyClosed, 0).error, Error::kOk);
  estop.on = false;
  r.run_ms(20);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kNone);
  estop.on = true;
  r.run_ms(10);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kEstop);
}

TEST_F(Estop, RotctldResetIsRefusedWhileActive) {
  estop.on = false;
  r.run_ms(10);
  protocol::RotctldSession rotctld(*r.controller, "9");
  testing::StringSink sink;
  rotctld.receive("R 1\nS\n", sink);
  EXPECT_EQ(sink.data, "RPRT -9\nRPRT 0\n");  // stop always answers
}

}  // namespace
}  // namespace rotord
