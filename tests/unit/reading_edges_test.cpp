// Readings on the edges, as every protocol prints them (issue 10, items 2
// to 5): a bearing a hair below 360 is 0, never 360; a rotator resting a
// little beyond a range end reads that end; WRC MONITOR pushes the firmware's
// lines; rotctld's \pause runs on the transport's clock.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "fake_rotator.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;
using testing::FakeRotator;
using testing::StringSink;

/// Powers the controller up again with the azimuth pot at `az_deg` and the
/// given offset, so the reading starts there without a plausibility jump.
void restart_at(FakeRotator& r, float az_deg, double offset_deg) {
  r.settings.set(Id::kAzOffsetDeg, offset_deg);
  r.az.set_deg(az_deg);
  r.controller = std::make_unique<Controller>(r.settings, r.az.io(), r.el.io());
  r.controller->begin(r.now);
  r.run_ms(100);
}

std::string ask(Session& session, const std::string& bytes) {
  StringSink sink;
  session.receive(bytes, sink);
  return sink.data;
}

TEST(ReadingEdges, EasycommNeverAnswersABearingOf360) {
  FakeRotator r;  // az 0..450: 359.97 is a position inside the travel
  restart_at(r, 360.0f, -0.03);
  ASSERT_NEAR(r.controller->status().az.position_deg, 359.97f, 0.001f);
  EasycommSession easycomm(*r.controller, "9.9.9");
  EXPECT_EQ(ask(easycomm, "AZ\n"), "AZ0.0\n");
}

TEST(ReadingEdges, AnEndlessAxisReportsABearingThatRoundsToZero) {
  FakeRotator r;
  r.settings.set(Id::kAzContinuous, 1);
  restart_at(r, 360.0f, -0.03);  // bearing 359.97
  ASSERT_NEAR(r.controller->status().az.position_deg, 359.97f, 0.001f);
  WrcSession wrc(*r.controller, "9.9.9");
  EXPECT_EQ(ask(wrc, "AZ?\n"), "OK AZ 0.0\r\n");
  EXPECT_EQ(ask(wrc, "STATE\n"), "OK STATE AZ=0.0 EL=20.0 SPEED=100 FLAGS=\r\n");
  SeedSession seed(*r.controller);
  EXPECT_EQ(ask(seed, "$Q\n").rfind("$Q,0.0,20.0,", 0), 0u);
  Gs232Session gs232(*r.controller);
  const std::string c = ask(gs232, "C\r");
  EXPECT_EQ(c.find("360"), std::string::npos) << c;
  EXPECT_NE(c.find("000"), std::string::npos) << c;

  restart_at(r, 360.0f, -0.003);  // bearing 359.997, for two decimals
  RotctldSession rotctld(*r.controller, "9.9.9");
  EXPECT_EQ(ask(rotctld, "p\n"), "0.00\n20.00\n");
}

TEST(ReadingEdges, ARotatorRestingJustBeyondARangeEndReadsThatEnd) {
  FakeRotator r;  // az 10..450 here, tolerance 1 deg
  r.settings.set(Id::kAzMinDeg, 10);
  restart_at(r, 10.0f, -0.14);
  EXPECT_FLOAT_EQ(r.controller->status().az.position_deg, 10.0f);
  RotctldSession rotctld(*r.controller, "9.9.9");
  EXPECT_EQ(ask(rotctld, "p\n"), "10.00\n20.00\n");

  restart_at(r, 450.0f, 0.16);
  EXPECT_FLOAT_EQ(r.controller->status().az.position_deg, 450.0f);
  RotctldSession after_restart(*r.controller, "9.9.9");
  EXPECT_EQ(ask(after_restart, "p\n"), "450.00\n20.00\n");
  EXPECT_TRUE(r.controller->status().az.limit_cw);
}

TEST(ReadingEdges, ARealOvertravelStaysVisible) {
  FakeRotator r;
  r.settings.set(Id::kAzMinDeg, 10);
  restart_at(r, 10.0f, -1.5);  // beyond the 1 deg tolerance
  EXPECT_NEAR(r.controller->status().az.position_deg, 8.5f, 0.001f);
  restart_at(r, 450.0f, 2.0);
  EXPECT_NEAR(r.controller->status().az.position_deg, 452.0f, 0.001f);
}

TEST(ReadingEdges, TheMonitorTapGetsOneLinePerPeriodHoweverManyClientsMonitor) {
  FakeRotator r;
  StringSink log_port;
  MonitorTap tap(log_port);
  WrcSession a(*r.controller, "9.9.9", &tap);
  WrcSession b(*r.controller, "9.9.9", &tap);
  EXPECT_EQ(ask(a, "MONITOR 1\n"), "OK MONITOR 1\r\n");
  EXPECT_EQ(ask(b, "MONITOR 1\n"), "OK MONITOR 1\r\n");
  StringSink to_a, to_b;
  for (Millis t = 10; t <= 1000; t += 10) {
    a.poll(t, to_a);
    b.poll(t, to_b);
  }
  EXPECT_EQ(to_a.writes, 10);
  EXPECT_EQ(to_b.writes, 10);
  EXPECT_EQ(log_port.writes, 10);
  EXPECT_EQ(log_port.data.rfind("STATE AZ=100.0 EL=20.0 SPEED=100 FLAGS=\r\n", 0), 0u)
      << log_port.data;
}

TEST(ReadingEdges, RotctldPauseRunsOnTheTransportClockNotControllerTime) {
  // As under `rotord --speedup 10` after 3 s: 30 s of controller time.
  FakeRotator r;
  r.run_ms(30000);
  RotctldSession rotctld(*r.controller, "9.9.9");
  StringSink sink;
  rotctld.poll(3000, sink);
  EXPECT_EQ(ask(rotctld, "\\pause 1\n"), "");
  rotctld.poll(3010, sink);  // the transport's next poll starts the pause
  rotctld.poll(3500, sink);
  EXPECT_EQ(sink.data, "");
  rotctld.poll(4010, sink);
  EXPECT_EQ(sink.data, "RPRT 0\n");
}

}  // namespace
}  // namespace rotord::protocol
