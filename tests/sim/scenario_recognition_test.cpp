// Recognising the pass a client's go-tos follow (docs/tracking.md, "Trackers
// through the protocols") on the physics simulator, in virtual time: a
// Gpredict-style client through rotctld streams the ISS's pass through north
// over Boulder with the ISS in the TLE store; rotord recognises it after a
// few go-tos and follows the planned pass between them; a departing go-to,
// STOP, PARK and another client end it and are obeyed; without TLEs or a
// position, for a zig-zag and for two objects on one orbit nothing is
// recognised.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "../unit/iss_elements.hpp"
#include "../unit/string_sink.hpp"
#include "bench/sky_angle.hpp"
#include "hal/wall_clock.hpp"
#include "pass_bench.hpp"
#include "pass_client.hpp"
#include "protocol/rotctld_session.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "tracking/julian.hpp"
#include "tracking/sky_target.hpp"
#include "tracking/tle.hpp"
#include "tracking/tle_catalog.hpp"

namespace rotord {
namespace {

using settings::Id;

using testing::ask;
using testing::kIssLine1;
using testing::kIssLine2;

/// The shared pass bench (pass_bench.hpp) with the elevation kept below the
/// zenith and a TLE store, whose clock and store the controller is given.
class Bench : public testing::PassBench {
 public:
  Bench(const char* profile, double az0, double el0) : PassBench(profile, az0, el0) {
    settings().set(Id::kElMaxDeg, 90.0);  // the G-5500 without flip
  }
  void store_iss() { ASSERT_TRUE(catalog_.put(testing::iss_tle_text(), 0).ok()); }
  void store_twin() { ASSERT_TRUE(catalog_.put(testing::twin_tle_text(), 0).ok()); }
  const Recognition& recognition() { return controller().recognition(); }

 private:
  void attach(Controller& c) override {
    c.attach_utc_clock(this);
    c.attach_catalog(&catalog_);
  }
  tracking::TleCatalog catalog_;
};

/// What the client did over a pass.
struct ClientRun {
  int commands = 0;
  int refused = 0;
  int recognised_at = -1;           ///< the command that began the recognition
  double max_readback_gap_deg = 0;  ///< |read-back - target|, az in the client's frame
  int far_readings = 0;             ///< read-backs more than 90 deg from the client's target
  double max_error_deg = 0;         ///< antenna to the ISS on the sky, once recognised
};

/// The frame a client sends in.
enum class Frame {
  kPlain,   ///< az 0..360, el 0..90
  kFlip,    ///< Gpredict with max el 180: az + 180, 180 - el, the whole pass
  kMirror,  ///< the SatNOGS client: plain up to culmination, the flip frame after it
};

/// Gpredict as its source reads: a cycle of 1 s, `p`, then `P az el` with the
/// ISS's 0..360 azimuth when off by more than `threshold_deg`, in `frame`.
/// `each` runs after every go-to with its number and may end the run (false).
ClientRun gpredict(Bench& b, protocol::RotctldSession& client, double threshold_deg, Frame frame,
                   const std::function<bool(int)>& each = nullptr) {
  ClientRun run;
  double sent_az = -1, sent_el = 0;
  std::int64_t culmination_ms = 0;  // of this pass (max el 13.9 deg)
  EXPECT_TRUE(tracking::parse_utc("2019-12-09T22:49:32Z", culmination_ms));
  testing::each_second_of_the_iss_pass(b, [&](int, const tracking::LookAngles& look) {
    double az = look.az_deg, el = look.el_deg;
    if (frame == Frame::kFlip || (frame == Frame::kMirror && *b.unix_ms() >= culmination_ms)) {
      az = std::fmod(az + 180.0, 360.0);
      el = 180.0 - el;
    }
    double read_az = 0, read_el = 0;
    testing::read_position(client, read_az, read_el);
    if (sent_az >= 0) {
      // As the client compares them: its target now with what it reads.
      const double gap = std::fabs(read_az - az);
      if (gap > 90.0) {
        ++run.far_readings;
      } else {
        run.max_readback_gap_deg = std::fmax(run.max_readback_gap_deg, gap);
      }
      if (sent_el > 90.0) {
        EXPECT_GT(read_el, 90.0 - 1.0) << "read back out of its flip frame";
      }
    }
    if (b.recognition().active) {
      const double e = bench::sky_angle_deg(b.theta(AxisId::kAz), b.theta(AxisId::kEl), look.az_deg,
                                            look.el_deg);
      run.max_error_deg = std::fmax(run.max_error_deg, e);
    }
    if (std::fabs(az - read_az) > threshold_deg || std::fabs(el - read_el) > threshold_deg) {
      const bool before = b.recognition().active;
      if (!testing::send_goto(client, az, el)) ++run.refused;
      ++run.commands;
      sent_az = std::round(az * 100.0) / 100.0;
      sent_el = el;
      if (!before && b.recognition().active && run.recognised_at < 0)
        run.recognised_at = run.commands;
      if (each && !each(run.commands)) return false;
    }
    return true;
  });
  return run;
}

TEST(RecognitionScenario, AnIssPassStreamIsRecognisedAndFollowedThroughNorth) {
  Bench b("g5500", 300.0, 0.0);
  b.store_iss();
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  client.set_peer(access::Peer::from_ipv4(0x7f000001));
  const ClientRun run = gpredict(b, client, 5.0, Frame::kPlain);
  std::printf(
      "[ recognition ] g5500, ISS through north, Gpredict threshold 5: recognised at go-to %d, "
      "%d go-tos, %d refused, az %.0f..%.0f, max error %.1f deg while recognised, read-back at "
      "most %.1f deg from its target (%d readings 90+ deg off), ended: %s\n",
      run.recognised_at, run.commands, run.refused, b.min_az(), b.max_az(), run.max_error_deg,
      run.max_readback_gap_deg, run.far_readings, recognition_end_name(b.recognition().ended));
  // Never at the first go-to (a single one is literal). Standing 12 deg
  // from where the pass begins, the client re-sends its first target a
  // second later while the antenna turns: that step says nothing of the
  // ISS's motion, so its third go-to is the one recognised.
  ASSERT_GE(run.recognised_at, 2);
  EXPECT_LE(run.recognised_at, GotoMatcher::kMinHits + 2);
  EXPECT_STREQ(b.recognition().name, "ISS (ZARYA)");
  EXPECT_EQ(b.recognition().catalog, 25544u);
  EXPECT_EQ(b.recognition().begun, 1u);
  // Followed to LOS: on into the overlap, never the long way, no refusal.
  EXPECT_EQ(b.recognition().ended, RecognitionEnd::kLos);
  EXPECT_GT(b.max_az(), 400.0);
  EXPECT_GT(b.min_az(), 290.0);
  EXPECT_EQ(b.limit_ticks(), 0);
  EXPECT_EQ(run.refused, 0);
  // The client reads its own frame: never 360 deg from its target (at most
  // one reading in the second the antenna, a lag ahead, crosses north first).
  EXPECT_LT(run.max_readback_gap_deg, 10.0);
  EXPECT_LE(run.far_readings, 1);
  EXPECT_LT(run.max_error_deg, 5.0);
}

TEST(RecognitionScenario, AThresholdClientIsRecognisedAtItsSecondGotoInStep) {
  // Parked where the pass begins, as a tracker's pre-positioning leaves it:
  // Gpredict (5 deg) sends its first go-to when the ISS is 5 deg away and
  // its second a threshold later. Their step is the ISS's own motion over
  // that time: recognised at the second, not the third.
  tracking::Tle tle;
  ASSERT_TRUE(tracking::parse_tle(kIssLine1, kIssLine2, tle).ok());
  tracking::SkyTarget sat;
  ASSERT_EQ(sat.set_satellite(tle), tracking::Sgp4Error::kOk);
  Bench probe("g5500", 0.0, 0.0);
  const tracking::Observer station(tracking::Geodetic{40.015, -105.27, 1655.0});
  tracking::LookAngles aos;
  for (std::int64_t t = *probe.unix_ms(); t < *probe.unix_ms() + 1800000; t += 1000) {
    ASSERT_EQ(sat.look(t, station, aos), tracking::Sgp4Error::kOk);
    if (aos.el_deg >= 0.0) break;
  }
  ASSERT_GE(aos.el_deg, 0.0);
  Bench b("g5500", aos.az_deg, 0.0);
  b.store_iss();
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  const ClientRun run = gpredict(b, client, 5.0, Frame::kPlain);
  std::printf(
      "[ recognition ] parked at AOS (az %.1f), Gpredict threshold 5: recognised at go-to "
      "%d, %d go-tos, %d refused, max error %.1f deg while recognised, ended: %s\n",
      aos.az_deg, run.recognised_at, run.commands, run.refused, run.max_error_deg,
      recognition_end_name(b.recognition().ended));
  EXPECT_EQ(run.recognised_at, 2);
  EXPECT_EQ(b.recognition().ended, RecognitionEnd::kLos);
  EXPECT_EQ(run.refused, 0);
  EXPECT_GT(b.max_az(), 400.0);
  EXPECT_LT(run.max_error_deg, 5.0);
  EXPECT_EQ(b.limit_ticks(), 0);
}

TEST(RecognitionScenario, AFlipStreamIsRecognisedAndReadBackInItsFrame) {
  // Gpredict with max el 180 on a G-5500 0..180: az + 180, 180 - el.
  Bench b("g5500", 130.0, 170.0);
  b.settings().set(Id::kElMaxDeg, 180.0);
  b.store_iss();
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  const ClientRun run = gpredict(b, client, 5.0, Frame::kFlip);
  std::printf(
      "[ recognition ] flip frame: recognised at go-to %d, %d go-tos, %d refused, max "
      "error %.1f deg, read-back at most %.1f deg from its target (%d 90+ off)\n",
      run.recognised_at, run.commands, run.refused, run.max_error_deg, run.max_readback_gap_deg,
      run.far_readings);
  ASSERT_GE(run.recognised_at, 2);
  EXPECT_EQ(run.refused, 0);
  EXPECT_LT(run.max_readback_gap_deg, 10.0);
  EXPECT_LE(run.far_readings, 1);
  EXPECT_EQ(b.limit_ticks(), 0);
}

TEST(RecognitionScenario, TheSatnogsMirroredPassStaysRecognisedThroughCulmination) {
  // The SatNOGS client (threshold 4) mirrors the pass at culmination: its
  // azimuth jumps by 180 deg and its elevation goes over 90. The same
  // object in the sky: still recognised, to LOS, nothing refused.
  Bench b("g5500", 300.0, 0.0);
  b.settings().set(Id::kElMaxDeg, 180.0);
  b.store_iss();
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  const ClientRun run = gpredict(b, client, 4.0, Frame::kMirror);
  std::printf(
      "[ recognition ] SatNOGS mirrored pass: recognised at go-to %d, %d go-tos, %d refused, max "
      "error %.1f deg, read-back at most %.1f deg from its target (%d 90+ off), ended: %s\n",
      run.recognised_at, run.commands, run.refused, run.max_error_deg, run.max_readback_gap_deg,
      run.far_readings, recognition_end_name(b.recognition().ended));
  ASSERT_GE(run.recognised_at, 2);
  EXPECT_EQ(b.recognition().begun, 1u);
  EXPECT_EQ(b.recognition().ended, RecognitionEnd::kLos);
  EXPECT_EQ(run.refused, 0);
  EXPECT_LE(run.far_readings, 2);
  EXPECT_LT(run.max_error_deg, 5.0);
  EXPECT_EQ(b.limit_ticks(), 0);
}

/// Runs the ISS stream until recognised and a few go-tos more.
void until_recognised(Bench& b, protocol::RotctldSession& client) {
  gpredict(b, client, 5.0, Frame::kPlain, [&](int) { return !b.recognition().active; });
  ASSERT_TRUE(b.recognition().active);
  b.run_ms(20000);  // planned and following
  ASSERT_EQ(b.controller().status().mode, Mode::kTrack);
}

TEST(RecognitionScenario, ADepartingGotoEndsItAndIsObeyedLiterally) {
  Bench b("g5500", 300.0, 0.0);
  b.store_iss();
  b.power_on();
  protocol::RotctldSession client(b.controller(), "test");
  until_recognised(b, client);
  ASSERT_EQ(ask(client, "P 180 45\n"), "RPRT 0\n");
  EXPECT_FALSE(b.recognition().active);
  EXPECT_EQ(b.recognition().ended, RecognitionEnd::kDeparted);
  b.settle();
  EXPECT_NEAR(b.theta(AxisId::kAz), 180.0, 2.0);
  EXPECT_NEAR(b.theta(AxisId::kEl), 45.0, 2.0);
  EXPECT_NE(b.controller().status().mode, Mode::kTrack);
}

TEST(RecognitionScenario, StopParkAndAnotherClientEndIt) {
  {
    Bench b("g5500", 300.0, 0.0);
    b.store_iss();
    b.power_on();
    protocol::RotctldSession client(b.controller(), "test");
    until_recognised(b, client);
    ASSERT_EQ(ask(client, "S\n"), "RPRT 0\n");
    EXPECT_EQ(b.recognition().ended, RecognitionEnd::kStop);
    b.run_ms(3000);
    EXPECT_FALSE(b.controller().status().moving());
    EXPECT_EQ(b.controller().status().mode, Mode::kIdle);
  }
  {
    Bench b("g5500", 300.0, 0.0);
    b.store_iss();
    b.settings().set(Id::kParkAzDeg, 200.0);
    b.settings().set(Id::kParkElDeg, 5.0);
    b.power_on();
    protocol::RotctldSession client(b.controller(), "test");
    until_recognised(b, client);
    ASSERT_EQ(ask(client, "K\n"), "RPRT 0\n");
    EXPECT_EQ(b.recognition().ended, RecognitionEnd::kPark);
    b.settle();
    EXPECT_NEAR(b.theta(AxisId::kAz), 200.0, 2.0);
  }
  {
    Bench b("g5500", 300.0, 0.0);
    b.store_iss();
    b.power_on();
    protocol::RotctldSession client(b.controller(), "test");
    protocol::RotctldSession other(b.controller(), "test");
    until_recognised(b, client);
    ASSERT_EQ(ask(other, "P 100 20\n"), "RPRT 0\n");
    EXPECT_EQ(b.recognition().ended, RecognitionEnd::kOtherSource);
    b.settle();
    EXPECT_NEAR(b.theta(AxisId::kAz), 100.0, 2.0);
  }
}

TEST(RecognitionScenario, NothingWithoutTlesOrWithoutAPositionOrWhenOff) {
  for (int variant = 0; variant < 3; ++variant) {
    Bench b("g5500", 300.0, 0.0);
    if (variant != 0) b.store_iss();
    if (variant == 2) b.settings().set(Id::kTrackRecognise, 0.0);
    b.power_on();
    protocol::RotctldSession client(b.controller(), "test");
    // The client's stream is computed for Boulder; without a position the
    // controller has none to compare it with.
    gpredict(b, client, 5.0, Frame::kPlain, [&](int n) {
      if (variant == 1 && n == 1) b.settings().set(Id::kStationLatDeg, 0.0);
      if (variant == 1 && n == 1) b.settings().set(Id::kStationLonDeg, 0.0);
      return n < 12;
    });
    EXPECT_EQ(b.recognition().begun, 0u) << "variant " << variant;
    EXPECT_GT(b.max_az(), 360.0) << "the continuity rule still holds, variant " << variant;
  }
}

TEST(RecognitionScenario, AZigZagOrTwoObjectsOnOneOrbitAreNotRecognised) {
  // Alternately 1.5 deg either side of the ISS, every go-to near it: a
  // zig-zag. The same go-tos 1.5 deg to one side are a tracker's.
  for (const bool zigzag : {true, false}) {
    Bench b("g5500", 300.0, 0.0);
    b.store_iss();
    b.power_on();
    protocol::RotctldSession client(b.controller(), "test");
    tracking::Tle tle;
    ASSERT_TRUE(tracking::parse_tle(kIssLine1, kIssLine2, tle).ok());
    tracking::SkyTarget sat;
    ASSERT_EQ(sat.set_satellite(tle), tracking::Sgp4Error::kOk);
    const tracking::Observer station = b.controller().observer();
    for (int n = 0; n < 1200; ++n) {  // until the ISS is up
      tracking::LookAngles look;
      ASSERT_EQ(sat.look(*b.unix_ms(), station, look), tracking::Sgp4Error::kOk);
      if (look.el_deg > 0.0) break;
      b.run_ms(5000);
    }
    b.run_ms(120000);
    for (int n = 0; n < 12; ++n) {
      tracking::LookAngles look;
      ASSERT_EQ(sat.look(*b.unix_ms(), station, look), tracking::Sgp4Error::kOk);
      ASSERT_GT(look.el_deg, 0.0);
      const double offset = zigzag && n % 2 == 0 ? -1.5 : 1.5;
      char cmd[64];
      std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", std::fmod(look.az_deg + offset, 360.0),
                    look.el_deg);
      ASSERT_EQ(ask(client, cmd), "RPRT 0\n");
      b.run_ms(2000);
    }
    EXPECT_EQ(b.recognition().begun, zigzag ? 0u : 1u) << (zigzag ? "zig-zag" : "steady");
  }
  {
    Bench b("g5500", 300.0, 0.0);
    b.store_iss();
    b.store_twin();
    b.power_on();
    protocol::RotctldSession client(b.controller(), "test");
    gpredict(b, client, 5.0, Frame::kPlain);
    EXPECT_EQ(b.recognition().begun, 0u);
    EXPECT_GT(b.max_az(), 400.0);  // the continuity rule alone
  }
}

}  // namespace
}  // namespace rotord
