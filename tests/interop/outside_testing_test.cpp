// The defects that testing rotord from outside found (issue 10), each
// reproduced through the real daemon the way it was seen: Hamlib's model 603
// slowing the shared speed before a long rotctld move, Hamlib's model 2
// refusing a position it read back, rotctld's \pause under --speedup.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "poll.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

/// rotctld's `p`: two lines, azimuth and elevation.
bool read_position(TcpClient& rotctld, double& az, double& el) {
  std::string a, e;
  if (!rotctld.send("p\n") || !rotctld.read_line(a) || !rotctld.read_line(e)) return false;
  az = std::atof(a.c_str());
  el = std::atof(e.c_str());
  return true;
}

/// Advances controller time a second at a time (at most `seconds`) until the
/// azimuth is within 1 deg of `az`, or a fault shows.
bool wait_for_az(DaemonProcess& daemon, TcpClient& rotctld, TcpClient& wrc, double target_az,
                 int seconds) {
  for (int n = 0; n < seconds; ++n) {
    double az = 0, el = 0;
    if (!read_position(rotctld, az, el)) return false;
    if (std::fabs(az - target_az) <= 1.0) return true;
    if (wrc.ask("FAULT?\n") != "OK FAULT AZ=NONE EL=NONE") return false;
    if (daemon.advance_ms(1000) < 0) return false;
  }
  return false;
}

TEST(OutsideTesting, AFullTravelMoveAtHalfSpeedArrivesWithoutATimeout) {
  // SPID, az -180..540, PWM with a dead band; 720 deg at speed 50 is ~200 s
  // of simulated time, beyond the old fixed 180 s timeout.
  DaemonProcess daemon({"--sim", "spid", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  TcpClient rotctld(daemon.ports().rotctld);
  TcpClient wrc(daemon.ports().wrc);
  TcpClient gs232(daemon.ports().gs232);
  EXPECT_EQ(rotctld.ask("P 540 10\n"), "RPRT 0");
  ASSERT_TRUE(wait_for_az(daemon, rotctld, wrc, 540.0, 400)) << wrc.ask("FAULT?\n");
  // Hamlib's model 603 sends X2 before its manual moves; the speed is shared.
  gs232.send("X2\r");
  EXPECT_EQ(wrc.ask("SPEED?\n"), "OK SPEED 50");
  EXPECT_EQ(rotctld.ask("P -180 10\n"), "RPRT 0");
  EXPECT_TRUE(wait_for_az(daemon, rotctld, wrc, -180.0, 600)) << wrc.ask("FAULT?\n");
  EXPECT_EQ(wrc.ask("FAULT?\n"), "OK FAULT AZ=NONE EL=NONE");
}

TEST(OutsideTesting, HamlibModel2CanSendBackThePositionItReadAtTheRangeEnds) {
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const std::string where = "127.0.0.1:" + std::to_string(daemon.ports().rotctld);
  auto rotctl = [&](const std::string& commands) {
    return run_command("timeout 20 rotctl -m 2 -r " + where + " " + commands);
  };
  TcpClient rotctld(daemon.ports().rotctld);
  TcpClient wrc(daemon.ports().wrc);
  for (const char* ends : {"450 180", "0 0"}) {
    ASSERT_EQ(rotctl(std::string("P ") + ends).rc, 0) << ends;
    const double target_az = std::atof(ends);
    ASSERT_TRUE(wait_for_az(daemon, rotctld, wrc, target_az, 400)) << ends;
    daemon.advance_ms(30000);  // the coast, the elevation's arrival, the last readings
    const CommandOutput read = rotctl("p");
    ASSERT_EQ(read.rc, 0) << read.out;
    const std::vector<double> p = numbers_in(read.out);
    ASSERT_EQ(p.size(), 2u) << read.out;
    EXPECT_GE(p[0], 0.0);
    EXPECT_LE(p[0], 450.0);
    EXPECT_GE(p[1], 0.0);
    EXPECT_LE(p[1], 180.0);
    // Sent back exactly as read: model 2 refuses anything outside the limits
    // that \dump_state gave it.
    char again[64];
    std::snprintf(again, sizeof(again), "P %.2f %.2f", p[0], p[1]);
    const CommandOutput resent = rotctl(again);
    EXPECT_EQ(resent.rc, 0) << again << ": " << resent.out;
  }
}

TEST(OutsideTesting, RotctldPauseLastsItsSecondsOfWallTimeUnderSpeedup) {
  // Wall time on purpose: the defect is the mix of --speedup's controller
  // time with the wall clock.
  DaemonProcess daemon({"--sim", "g5500", "--speedup", "50"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  // Let controller time run well ahead of the wall clock (100 s simulated,
  // 2 s of wall time): the old pause compared the two and lasted ~100 s.
  poll_until(
      [&] {
        return json_number(http(daemon.ports().web, "GET", "/api/status").body, "time_ms") >=
               100000;
      },
      std::chrono::seconds(20));
  TcpClient rotctld(daemon.ports().rotctld);
  ASSERT_TRUE(rotctld.send("\\pause 1\np\n"));
  std::string line;
  // Bounded wait for liveness, not a timing assertion: the reply comes.
  ASSERT_TRUE(rotctld.read_line(line, 20000));
  EXPECT_EQ(line, "RPRT 0");
  ASSERT_TRUE(rotctld.read_line(line, 5000));
}

}  // namespace
}  // namespace rotord::testing
