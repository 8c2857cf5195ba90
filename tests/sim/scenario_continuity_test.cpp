// The continuity rule (docs/tracking.md, "Trackers through the protocols")
// on the physics simulator, in virtual time: a tracker that sends 0..360
// azimuths through a protocol session (Gpredict through rotctld, and the
// same stream through GS-232, Easycomm and WRC) follows a pass through north
// into the overlap with no unwind, and reads the position back in its own
// frame; a single go-to, a zig-zag, a STOP and the travel's end stay literal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "../unit/string_sink.hpp"
#include "bench/sky_angle.hpp"
#include "pass_bench.hpp"
#include "pass_client.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/wrc_session.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "tracking/sky_target.hpp"

namespace rotord {
namespace {

using settings::Id;

using testing::ask;
/// A rotator on the simulator at Boulder, its controller and a clock for the sky.
using Bench = testing::PassBench;

/// What a Gpredict-style client through rotctld measured over a pass.
struct PassRun {
  double max_error_deg = 0;         ///< the angle on the sky
  double max_readback_gap_deg = 0;  ///< |read-back az - last sent az|, in the client's frame
  int commands = 0;
  int refused = 0;
};

/// The pointing error: the angle on the sky (bench/sky_angle.hpp).
double great_circle_deg(double az1, double el1, double az2, double el2) {
  return bench::sky_angle_deg(az1, el1, az2, el2);
}

/// Gpredict as its source reads (gtk-rot-ctrl.c): a cycle of 1 s, `p`, then
/// `P az el` with the satellite's 0..360 azimuth when it is off by more than
/// the threshold on either axis. The ISS's pass of 2019-12-09 22:3x UTC over
/// Boulder rises at 312 deg and sets at 74 through north.
PassRun gpredict_pass(Bench& b, double threshold_deg) {
  protocol::RotctldSession gpredict(b.controller(), "test");
  gpredict.set_peer(access::Peer::from_ipv4(0x7f000001));
  PassRun run;
  double sent_az = -1;
  testing::each_second_of_the_iss_pass(b, [&](int cycle, const tracking::LookAngles& look) {
    double read_az = 0, read_el = 0;
    testing::read_position(gpredict, read_az, read_el);
    if (sent_az >= 0)
      run.max_readback_gap_deg = std::fmax(run.max_readback_gap_deg, std::fabs(read_az - sent_az));
    if (cycle > 0 && sent_az >= 0) {
      const double e = great_circle_deg(std::fmod(b.theta(AxisId::kAz), 360.0),
                                        b.theta(AxisId::kEl), look.az_deg, look.el_deg);
      // Judged once the antenna has reached the pass (AOS pre-positioning excluded).
      if (run.commands > 3) run.max_error_deg = std::fmax(run.max_error_deg, e);
    }
    if (std::fabs(look.az_deg - read_az) > threshold_deg ||
        std::fabs(look.el_deg - read_el) > threshold_deg) {
      const bool taken = testing::send_goto(gpredict, look.az_deg, look.el_deg);
      ++run.commands;
      if (!taken) ++run.refused;
      sent_az = std::round(look.az_deg * 100.0) / 100.0;
    }
    return true;
  });
  return run;
}

TEST(ContinuityScenario, GpredictPassThroughNorthRunsIntoTheOverlapOfA450DegRotator) {
  // G-5500 without flip (el 0..90), antenna at 300.
  Bench b("g5500", 300.0, 0.0);
  b.settings().set(Id::kElMaxDeg, 90.0);
  b.power_on();
  const PassRun run = gpredict_pass(b, 5.0);
  std::printf(
      "[ continuity ] g5500 450 deg, ISS through north, Gpredict threshold 5: az %.0f..%.0f, max "
      "error %.1f deg, read-back at most %.1f deg from what was sent, %d commands, %d refused\n",
      b.min_az(), b.max_az(), run.max_error_deg, run.max_readback_gap_deg, run.commands,
      run.refused);
  EXPECT_GT(b.max_az(), 400.0);  // on into the overlap ...
  EXPECT_GT(b.min_az(), 290.0);  // ... never back the long way round
  EXPECT_EQ(b.limit_ticks(), 0);
  EXPECT_EQ(run.refused, 0);
  // The client reads its own frame: never 360 deg from what it sent.
  EXPECT_LT(run.max_readback_gap_deg, 30.0);
  // At most the client's threshold plus the plant's lag, the crossing included.
  EXPECT_LT(run.max_error_deg, 5.0 + 4.0);
  EXPECT_GT(b.controller().continuity_resolved(), 5u);
}

TEST(ContinuityScenario, WithTheRuleOffTheSamePassUnwindsTheLongWay) {
  // What the rule removes: Hamlib's literal meaning turns 300+ deg at north.
  Bench b("g5500", 300.0, 0.0);
  b.settings().set(Id::kElMaxDeg, 90.0);
  b.settings().set(Id::kTrackContinuity, 0.0);
  b.power_on();
  const PassRun run = gpredict_pass(b, 5.0);
  std::printf("[ continuity ] off: az %.0f..%.0f, max error %.1f deg\n", b.min_az(), b.max_az(),
              run.max_error_deg);
  EXPECT_LT(b.min_az(), 100.0);
  EXPECT_GT(run.max_error_deg, 45.0);
  EXPECT_EQ(b.controller().continuity_resolved(), 0u);
}

TEST(ContinuityScenario, GpredictPassThroughNorthOnSpidStaysOnOneTurn) {
  // SPID -180..540 (H-bridge, slow zones), the SatNOGS client's 4 deg
  // threshold: the stream goes on past 360 rather than back to 0.
  Bench b("spid", 300.0, 0.0);
  b.power_on();
  const PassRun run = gpredict_pass(b, 4.0);
  std::printf("[ continuity ] spid -180..540: az %.0f..%.0f, max error %.1f deg, %d commands\n",
              b.min_az(), b.max_az(), run.max_error_deg, run.commands);
  EXPECT_GT(b.max_az(), 400.0);
  EXPECT_EQ(b.limit_ticks(), 0);
  EXPECT_EQ(run.refused, 0);
  EXPECT_LT(run.max_readback_gap_deg, 30.0);
  EXPECT_LT(run.max_error_deg, 4.0 + 4.0);
}

TEST(ContinuityScenario, ASingleGotoAndAZigZagAreLiteral) {
  Bench b("g5500", 400.0, 10.0);
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  // A single go-to means what Hamlib means: 60 is 60, not 420.
  ASSERT_EQ(ask(client, "P 60 10\n"), "RPRT 0\n");
  b.settle();
  EXPECT_NEAR(b.theta(AxisId::kAz), 60.0, 2.0);
  // A stream to 355, then a zig-zag across north: 359, 1 (continued: 361),
  // 359, then 1 again is a zig-zag and literal.
  for (const char* cmd : {"P 350 10\n", "P 355 10\n", "P 359 10\n", "P 1 10\n"}) {
    ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
    b.settle();
  }
  EXPECT_NEAR(b.theta(AxisId::kAz), 361.0, 2.0);
  EXPECT_NEAR(std::stod(ask(client, "p\n")), 1.0, 2.0);  // in its frame
  ASSERT_EQ(ask(client, "P 359 10\n"), "RPRT 0\n");
  b.settle();
  ASSERT_EQ(ask(client, "P 1 10\n"), "RPRT 0\n");
  b.settle();
  EXPECT_NEAR(b.theta(AxisId::kAz), 1.0, 2.0);
  // A pause longer than a stream's: the next go-to is literal again.
  for (const char* cmd : {"P 350 10\n", "P 355 10\n"}) {
    ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
    b.settle();
  }
  b.run_ms(GotoStream::kMaxGapMs + 1000);
  ASSERT_EQ(ask(client, "P 2 10\n"), "RPRT 0\n");
  b.settle();
  EXPECT_NEAR(b.theta(AxisId::kAz), 2.0, 2.0);
}

TEST(ContinuityScenario, StopAnotherSourceAndTheTravelsEndAreObeyed) {
  Bench b("g5500", 430.0, 10.0);
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  protocol::RotctldSession other(b.controller(), "test");
  for (const char* cmd : {"P 70 10\n", "P 75 10\n"}) {
    ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
    b.settle();
  }
  EXPECT_NEAR(b.theta(AxisId::kAz), 75.0, 2.0);  // the first was literal
  for (const char* cmd : {"P 350 10\n", "P 355 10\n", "P 359 10\n", "P 3 10\n"}) {
    ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
    b.settle();
  }
  // Jumped: 350 is a new stream; 3 continues it at 363.
  EXPECT_NEAR(b.theta(AxisId::kAz), 363.0, 2.0);
  // STOP ends the stream: the next go-to is literal (the long way, as asked).
  ASSERT_EQ(ask(client, "S\n"), "RPRT 0\n");
  ASSERT_EQ(ask(client, "P 8 10\n"), "RPRT 0\n");
  b.run_ms(2000);
  EXPECT_LT(b.controller().status().az.target_deg, 10.0);
  ASSERT_EQ(ask(client, "S\n"), "RPRT 0\n");
  b.settle();
  // Near the end stop: the stream continues up to 450, never beyond it.
  for (const char* cmd : {"P 80 10\n", "P 82 10\n", "P 86 10\n", "P 89 10\n", "P 92 10\n"}) {
    ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
    b.settle();
    EXPECT_LE(b.controller().status().az.target_deg, 450.0f);
  }
  // 80 literal; 82, 86, 89 on the same turn; 92 too (no other turn fits).
  EXPECT_NEAR(b.theta(AxisId::kAz), 92.0, 2.0);
  for (const char* cmd : {"P 350 10\n", "P 355 10\n", "P 2 10\n"}) {
    ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
    b.settle();
  }
  EXPECT_NEAR(b.theta(AxisId::kAz), 362.0, 2.0);
  // Another source's go-to is its own (literal) stream.
  ASSERT_EQ(ask(other, "P 5 10\n"), "RPRT 0\n");
  b.settle();
  EXPECT_NEAR(b.theta(AxisId::kAz), 5.0, 2.0);
  EXPECT_EQ(b.limit_ticks(), 0);
}

/// A G-5500 at 330 deg, powered on, with the lead rule (which would put the
/// antenna up to a band past the last go-to) off: the turn each protocol
/// lands on is the stream's, to the degree.
std::unique_ptr<Bench> bench_without_lead() {
  auto b = std::make_unique<Bench>("g5500", 330.0, 10.0);
  b->settings().set(Id::kTrackStreamLead, 0.0);
  b->power_on();
  return b;
}

/// One stream across north through another protocol's session (`format`
/// prints one go-to): the antenna ends on the stream's turn, at 369.
void stream_across_north(protocol::Session& session, Bench& b, const char* format) {
  for (const double az : {340.0, 345.0, 350.0, 355.0, 359.0, 4.0, 9.0}) {
    char cmd[64];
    std::snprintf(cmd, sizeof cmd, format, az);
    ask(session, cmd);
    b.run_ms(1500);
  }
  b.settle();
  EXPECT_NEAR(b.theta(AxisId::kAz), 369.0, 2.0) << format;
}

TEST(ContinuityScenario, TheSameStreamThroughGs232EasycommAndWrc) {
  {
    const auto b = bench_without_lead();
    protocol::Gs232Session gs232(b->controller());
    stream_across_north(gs232, *b, "W%03.0f 010\r");
    // Read back in its frame: 009, not 369.
    EXPECT_NE(ask(gs232, "C\r").find("009"), std::string::npos) << ask(gs232, "C\r");
  }
  {
    // Easycomm and WRC read 0..360 as a bearing on the turn nearest the
    // antenna, which agrees with the stream while the antenna keeps up; the
    // stream keeps them on its turn either way.
    const auto b = bench_without_lead();
    protocol::EasycommSession easycomm(b->controller(), "test");
    stream_across_north(easycomm, *b, "AZ%.1f EL10.0\n");
  }
  {
    const auto b = bench_without_lead();
    protocol::WrcSession wrc(b->controller(), "test");
    stream_across_north(wrc, *b, "AZ %.1f\n");
    // WRC reads 0..360 as the bearing on the nearest turn and reports the
    // unwrapped position (docs/protocols): the rule agreed, nothing shifted.
    EXPECT_NE(ask(wrc, "AZ?\n").find("OK AZ 36"), std::string::npos) << ask(wrc, "AZ?\n");
  }
}

}  // namespace
}  // namespace rotord
