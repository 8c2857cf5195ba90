// The continuity rule through the real daemon and the real Hamlib client: one
// `rotctl -m 2` session (Debian's libhamlib-utils) streams a pass across
// north as Gpredict and the SatNOGS client send it (0..360, a go-to every
// 1.5 s of controller time); the simulated G-5500 (0..450) runs on into the
// overlap with no unwind, this client reads the position back in its own
// frame, and another client reads the unwrapped position.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "rotctl_session.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

/// What one streamed pass did.
struct Streamed {
  double lowest = 1e9, highest = -1e9;  ///< the antenna, as another client reads it
  double worst_gap = 0;                 ///< |the tracker's reading - what it sent|
  double end_mine = NAN, end_other = NAN;
};

/// The pass: AOS at 330 (the first go-to, literal; waited for), then 3 deg
/// per command every 1.5 s across north to 27, as a tracker sends it.
void stream_pass(DaemonProcess& daemon, RotctlSession& tracker, const std::string& where,
                 Streamed& r) {
  tracker.send("P 330 5\n");
  double az = NAN;
  for (int i = 0; i < 200; ++i) {
    ASSERT_GE(daemon.advance_ms(1000), 0);
    az = tracker.read_az();
    if (std::fabs(az - 330.0) < 2.0) break;
  }
  ASSERT_NEAR(az, 330.0, 2.0) << tracker.text();
  for (double sky = 333.0; sky < 390.0; sky += 3.0) {
    const double sent = std::fmod(sky, 360.0);
    char cmd[48];
    std::snprintf(cmd, sizeof cmd, "P %.2f 20\n", sent);
    tracker.send(cmd);
    for (int step = 0; step < 3; ++step) {
      ASSERT_GE(daemon.advance_ms(500), 0);
      // Another client's view: the unwrapped position.
      const CommandOutput o = run_command("timeout 20 rotctl -m 2 -r " + where + " p");
      const std::vector<double> v = numbers_in(o.out);
      ASSERT_EQ(v.size(), 2u) << o.out;
      r.lowest = std::fmin(r.lowest, v[0]);
      r.highest = std::fmax(r.highest, v[0]);
    }
    // The tracker's own view: the frame it sends in.
    const double mine = tracker.read_az();
    ASSERT_FALSE(std::isnan(mine)) << tracker.text();
    r.worst_gap = std::fmax(r.worst_gap, std::fabs(mine - sent));
  }
  for (int i = 0; i < 10; ++i) ASSERT_GE(daemon.advance_ms(1000), 0);
  r.end_mine = tracker.read_az();
  const std::vector<double> other =
      numbers_in(run_command("timeout 20 rotctl -m 2 -r " + where + " p").out);
  if (other.size() == 2) r.end_other = other[0];
}

TEST(TrackerStream, RotctlStreamingAPassAcrossNorthRunsIntoTheOverlap) {
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const std::string where = "127.0.0.1:" + std::to_string(daemon.ports().rotctld);
  RotctlSession tracker(where);
  ASSERT_TRUE(tracker.ok());
  Streamed r;
  stream_pass(daemon, tracker, where, r);
  std::printf(
      "[ continuity ] rotctl stream 333 -> 27 across north: antenna %.1f..%.1f, the tracker read "
      "at most %.1f deg from what it sent, ends reading %.2f (another client %.2f)\n",
      r.lowest, r.highest, r.worst_gap, r.end_mine, r.end_other);
  EXPECT_GT(r.lowest, 325.0) << "unwound the long way round";
  EXPECT_GT(r.highest, 380.0);
  EXPECT_LT(r.worst_gap, 10.0);
  EXPECT_NEAR(r.end_mine, 27.0, 2.0);
  EXPECT_NEAR(r.end_other, 387.0, 2.0);
  // STOP is obeyed at once; the next go-to is single, hence literal.
  tracker.send("S\n");
  tracker.send("P 40 20\n");
  for (int i = 0; i < 120; ++i) ASSERT_GE(daemon.advance_ms(1000), 0);
  EXPECT_NEAR(tracker.read_az(), 40.0, 2.0) << tracker.text();
  const std::vector<double> after =
      numbers_in(run_command("timeout 20 rotctl -m 2 -r " + where + " p").out);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_NEAR(after[0], 40.0, 2.0);
}

TEST(TrackerStream, WithTrackContinuityOffTheSameStreamTurnsTheLongWay) {
  // What the rule removes: Hamlib's literal meaning, 360 deg back at north.
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const std::string where = "127.0.0.1:" + std::to_string(daemon.ports().rotctld);
  {
    // Any settings key through rotctld's set_conf (rotctl maps only Hamlib's tokens).
    TcpClient setter(daemon.ports().rotctld);
    ASSERT_TRUE(setter.send("C track.continuity 0\n"));
    ASSERT_EQ(setter.recv_once(3000), "RPRT 0\n");
  }
  RotctlSession tracker(where);
  ASSERT_TRUE(tracker.ok());
  Streamed r;
  stream_pass(daemon, tracker, where, r);
  std::printf("[ continuity ] off: antenna %.1f..%.1f, ends at %.2f\n", r.lowest, r.highest,
              r.end_other);
  // Never into the overlap; after the stream still on its way back round.
  EXPECT_LT(r.highest, 360.0);
  EXPECT_LT(r.end_other, 300.0);
}

}  // namespace
}  // namespace rotord::testing

namespace rotord::testing {
namespace {

TEST(TrackerStream, RotctlStreamingASatnogsMirroredPassGoesOverTheTop) {
  // The SatNOGS client's flip as it sends it (past culmination az = 2 az_mid
  // - az, el = 2 el_mid - el): the azimuth turns back once, the elevation
  // goes on past 90. The simulated G-5500 (el 0..180) follows it over the
  // top, on the same turn, with the lead rule on (the default).
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const std::string where = "127.0.0.1:" + std::to_string(daemon.ports().rotctld);
  RotctlSession tracker(where);
  ASSERT_TRUE(tracker.ok());
  const auto other = [&where]() {
    return numbers_in(run_command("timeout 20 rotctl -m 2 -r " + where + " p").out);
  };
  tracker.send("P 100 60\n");
  std::vector<double> v;
  for (int i = 0; i < 200; ++i) {
    ASSERT_GE(daemon.advance_ms(1000), 0);
    v = other();
    if (v.size() == 2 && std::fabs(v[0] - 100.0) < 2.0 && std::fabs(v[1] - 60.0) < 2.0) break;
  }
  ASSERT_EQ(v.size(), 2u);
  ASSERT_NEAR(v[1], 60.0, 2.0);
  double az_lo = 1e9, az_hi = -1e9, el_hi = -1e9;
  for (int i = 1; i <= 20; ++i) {
    // Up to culmination at (127, 87), then mirrored back to (97, 117).
    const double az = i <= 9 ? 100.0 + 3.0 * i : 127.0 - 3.0 * (i - 9);
    const double el = i <= 9 ? 60.0 + 3.0 * i : 87.0 + 3.0 * (i - 9);
    char cmd[48];
    std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", az, el);
    tracker.send(cmd);
    for (int step = 0; step < 4; ++step) {
      ASSERT_GE(daemon.advance_ms(500), 0);
      v = other();
      ASSERT_EQ(v.size(), 2u);
      az_lo = std::fmin(az_lo, v[0]);
      az_hi = std::fmax(az_hi, v[0]);
      el_hi = std::fmax(el_hi, v[1]);
    }
  }
  for (int i = 0; i < 10; ++i) ASSERT_GE(daemon.advance_ms(1000), 0);
  v = other();
  ASSERT_EQ(v.size(), 2u);
  std::printf("[ flip ] rotctl mirrored stream: az %.1f..%.1f, el up to %.1f, ends at %.1f %.1f\n",
              az_lo, az_hi, el_hi, v[0], v[1]);
  EXPECT_GT(el_hi, 110.0);       // over the top, as sent
  EXPECT_GT(az_lo, 90.0);        // the azimuth turned back once ...
  EXPECT_LT(az_hi, 135.0);       // ... and never round
  EXPECT_NEAR(v[0], 97.0, 6.0);  // where it was sent, within the band
  EXPECT_NEAR(v[1], 117.0, 6.0);
}

}  // namespace
}  // namespace rotord::testing
