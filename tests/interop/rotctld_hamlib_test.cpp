// The rotctld port of a running rotord (simulated G-5500: az 0..450, el 0..180)
// driven by Hamlib's real NET rotctl client (rotctl -m 2, Debian
// libhamlib-utils 4.5.4) and by raw sockets that behave like Gpredict, a
// logger and a misbehaving client. The byte-for-byte comparison with the real
// rotctld is rotctld_compare.test.sh.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

class RotctldHamlib : public ::testing::Test {
 protected:
  /// The simulated G-5500 on a manual clock: controller time moves only by
  /// advance().
  void start() {
    daemon = std::make_unique<DaemonProcess>(
        std::vector<std::string>{"--sim", "g5500", "--clock", "manual"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    where = "127.0.0.1:" + std::to_string(daemon->ports().rotctld);
  }
  CommandOutput rotctl(const std::string& commands) {
    return run_command("timeout 20 rotctl -m 2 -r " + where + " " + commands);
  }
  /// Position as rotctl -m 2 reads it (the client parses our two `p` lines).
  std::vector<double> position() {
    const CommandOutput r = rotctl("p");
    const std::vector<double> v = numbers_in(r.out);
    return r.rc == 0 && v.size() == 2 ? v : std::vector<double>{};
  }
  /// Runs `ms` of controller time in the daemon.
  void advance(long long ms) { ASSERT_GE(daemon->advance_ms(ms), 0) << daemon->output(); }
  /// Polls until the rotator is within 1.5 deg of az/el, up to 400 s of
  /// controller time.
  std::vector<double> wait_for(double az, double el) {
    std::vector<double> p;
    for (int i = 0; i < 400; ++i) {
      p = position();
      if (p.size() == 2 && std::fabs(p[0] - az) < 1.5 && std::fabs(p[1] - el) < 1.5) break;
      advance(1000);
    }
    return p;
  }

  std::unique_ptr<DaemonProcess> daemon;
  std::string where;
};

TEST_F(RotctldHamlib, ModelTwoLearnsTheLimitsFromDumpState) {
  start();
  // Outside the limits we report, model 2 refuses before anything is sent.
  const CommandOutput refused = rotctl("P 451 20");
  EXPECT_NE(refused.rc, 0);
  EXPECT_NE(refused.out.find("range problem az=451.00(min=0.00,max=450.00)"), std::string::npos)
      << refused.out;
  const CommandOutput flip_refused = rotctl("P 10 181");
  EXPECT_NE(flip_refused.rc, 0) << flip_refused.out;
  // Inside them, even beyond model 2's defaults (-180..180, 0..90), it sends.
  EXPECT_EQ(rotctl("P 440 170").rc, 0);
  EXPECT_EQ(rotctl("S").rc, 0);
}

TEST_F(RotctldHamlib, SetAndReadPositionsThroughTheOverlapAndAFlip) {
  start();
  const CommandOutput set = rotctl("P 420 150");
  ASSERT_EQ(set.rc, 0) << set.out;
  TcpClient status(daemon->ports().rotctld);
  std::string flags;
  for (int i = 0; i < 100 && flags.find("MOVING_UP") == std::string::npos; ++i) {
    status.send("s\n");
    ASSERT_TRUE(status.read_line(flags));
    advance(100);
  }
  EXPECT_EQ(flags.rfind("MOVING MOVING_AZ MOVING_RIGHT MOVING_EL MOVING_UP", 0), 0u) << flags;
  std::vector<double> p = wait_for(420, 150);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 420, 1.5);  // reported unwrapped, not 60
  EXPECT_NEAR(p[1], 150, 1.5);
  for (int i = 0; i < 100; ++i) {  // until both axes have settled
    status.send("s\n");
    ASSERT_TRUE(status.read_line(flags));
    if (flags.find("MOVING") == std::string::npos) break;
    advance(1000);
  }
  EXPECT_EQ(flags, "OVERLAP_UP OVERLAP_RIGHT ");
  // 10 is 10: back through 360 the long way, as the client asked.
  ASSERT_EQ(rotctl("P 10 20").rc, 0);
  p = wait_for(10, 20);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 10, 1.5);
  EXPECT_NEAR(p[1], 20, 1.5);
}

TEST_F(RotctldHamlib, StopParkMoveResetInfo) {
  start();
  ASSERT_EQ(rotctl("M 16 50").rc, 0);
  TcpClient c(daemon->ports().rotctld);
  std::string line;
  for (int i = 0; i < 50 && line.find("MOVING_RIGHT") == std::string::npos; ++i) {
    c.send("s\n");
    ASSERT_TRUE(c.read_line(line));
    advance(100);
  }
  EXPECT_NE(line.find("MOVING_RIGHT"), std::string::npos) << line;
  ASSERT_EQ(rotctl("S").rc, 0);
  for (int i = 0; i < 100 && line.find("MOVING") != std::string::npos; ++i) {
    advance(500);
    c.send("s\n");
    ASSERT_TRUE(c.read_line(line));
  }
  EXPECT_EQ(line.find("MOVING"), std::string::npos) << line;
  // Park goes to park.az_deg / park.el_deg (0, 0 by default).
  ASSERT_EQ(rotctl("P 100 40").rc, 0);
  ASSERT_EQ(wait_for(100, 40).size(), 2u);
  ASSERT_EQ(rotctl("K").rc, 0);
  const std::vector<double> parked = wait_for(0, 0);
  ASSERT_EQ(parked.size(), 2u);
  EXPECT_NEAR(parked[0], 0, 1.5);
  EXPECT_NEAR(parked[1], 0, 1.5);
  ASSERT_EQ(rotctl("M UP 20").rc, 0);  // rotctl sends "M 2 20"
  ASSERT_EQ(rotctl("R 1").rc, 0);      // reset stops it
  const CommandOutput info = rotctl("_");
  EXPECT_EQ(info.rc, 0);
  EXPECT_EQ(info.out.rfind("rotord ", 0), 0u) << info.out;
  // Several commands in one run: model 2 sends them on one connection.
  const CommandOutput many = rotctl("P 30 10 p S _");
  EXPECT_EQ(many.rc, 0) << many.out;
}

TEST_F(RotctldHamlib, GpredictStyleClientTracksAMovingTargetWithoutDesync) {
  start();
  TcpClient gpredict(daemon->ports().rotctld);
  ASSERT_TRUE(gpredict.connected());
  // A pass: az 100 -> 250, el 10 -> 80 -> 10 over one simulated minute,
  // one cycle per 0.8 s of controller time.
  constexpr int kCycles = 75;
  double worst_az = 0;
  double last_az = 0;
  double last_el = 0;
  for (int i = 0; i < kCycles; ++i) {
    const double t = static_cast<double>(i) / (kCycles - 1);
    const double az = 100 + 150 * t;
    const double el = 10 + 70 * std::sin(std::numbers::pi * t);
    char cmd[64];
    std::snprintf(cmd, sizeof(cmd), "P %.2f %.2f\n", az, el);
    ASSERT_TRUE(gpredict.send(cmd));
    // Gpredict: one recv per reply, and it must be exactly the reply.
    ASSERT_EQ(gpredict.recv_once(3000), "RPRT 0\n") << "cycle " << i;
    advance(100);
    ASSERT_TRUE(gpredict.send("p\n"));
    const std::string reply = gpredict.recv_once(3000);
    const std::vector<double> v = numbers_in(reply);
    ASSERT_EQ(v.size(), 2u) << "cycle " << i << ": " << reply;
    ASSERT_EQ(std::count(reply.begin(), reply.end(), '\n'), 2) << reply;
    last_az = v[0];
    last_el = v[1];
    if (i > 20) worst_az = std::max(worst_az, std::fabs(v[0] - az));
    advance(700);
  }
  // The antenna follows the pass (the G-5500 runs 6 deg/s, the pass 2.5).
  EXPECT_LT(worst_az, 15.0);
  EXPECT_NEAR(last_az, 250, 15);
  EXPECT_LT(last_el, 40);
  gpredict.send("S\n");
  EXPECT_EQ(gpredict.recv_once(3000), "RPRT 0\n");
  gpredict.send("q\n");
  EXPECT_TRUE(gpredict.wait_closed());
}

TEST_F(RotctldHamlib, ManyClientsShareTheRotatorEachGetsItsOwnReplies) {
  start();
  TcpClient idle(daemon->ports().rotctld);
  TcpClient half(daemon->ports().rotctld);
  TcpClient logger(daemon->ports().rotctld);
  TcpClient tracker(daemon->ports().rotctld);
  ASSERT_TRUE(idle.connected() && half.connected() && logger.connected() && tracker.connected());
  ASSERT_TRUE(half.send("P 1"));  // a half-sent command must block nobody
  // A logger polls with the extended protocol while a tracker sets targets
  // and rotctl -m 2 connects and reads: every reply must be its own.
  // The logger polls for as long as the tracker works (at least 40 times),
  // so its requests interleave with the tracker's and rotctl's whatever the
  // machine's pace; the bound only ends a runaway.
  std::atomic<int> logger_errors{0};
  std::atomic<bool> tracker_done{false};
  std::thread logger_thread([&] {
    for (int i = 0; (i < 40 || !tracker_done) && i < 100000; ++i) {
      logger.send("+p\n");
      const std::string r = logger.recv_once(3000);
      if (r.rfind("get_pos:\nAzimuth: ", 0) != 0 || r.find("\nRPRT 0\n") == std::string::npos)
        ++logger_errors;
    }
  });
  for (int i = 0; i < 20; ++i) {
    tracker.send("P " + std::to_string(200 + i) + " 30\n");
    EXPECT_EQ(tracker.recv_once(3000), "RPRT 0\n");  // no ASSERT: the logger must be joined
    if (i % 5 == 0) {
      EXPECT_EQ(rotctl("p").rc, 0);
    }
  }
  tracker_done = true;
  logger_thread.join();
  EXPECT_EQ(logger_errors, 0);
  // The half-sent command completes on its own connection only.
  ASSERT_TRUE(half.send("0 20\n"));
  EXPECT_EQ(half.recv_once(3000), "RPRT 0\n");
  EXPECT_EQ(tracker.recv_once(200), "");
  // The idle connection is still served.
  EXPECT_EQ(idle.ask("\\dump_state\n"), "1");
}

TEST_F(RotctldHamlib, BadInputGetsErrorsAndNeverMovesOrStallsOthers) {
  start();
  TcpClient good(daemon->ports().rotctld);
  TcpClient bad(daemon->ports().rotctld);
  const double az_before = std::stod(good.ask("p\n"));
  std::string line;
  ASSERT_TRUE(good.read_line(line));
  const char garbage[] = "\x00\x01\xff\xfe\x80 \x00zz\n\x07\x1b[2J\n\x00\x00\x00\n";
  ASSERT_TRUE(bad.send(std::string(garbage, sizeof(garbage) - 1)));
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(bad.read_line(line));
    EXPECT_EQ(line, "RPRT -4");
  }
  EXPECT_EQ(bad.ask(std::string(1 << 20, 'z') + "\n"), "RPRT -4");
  EXPECT_EQ(bad.ask("P " + std::string(1 << 20, '7') + " 10\n"), "RPRT -1");
  std::string thousand;
  for (int i = 0; i < 1000; ++i) thousand += "v SPEED\n";
  ASSERT_TRUE(bad.send(thousand));
  int replies = 0;
  while (replies < 1000 && bad.read_line(line)) {
    if (line != "100") break;
    ++replies;
  }
  EXPECT_EQ(replies, 1000);
  EXPECT_EQ(good.ask("s\n").find("MOVING"), std::string::npos);  // nothing moves
  EXPECT_NEAR(std::stod(good.ask("p\n")), az_before, 0.5);       // sensor noise only
  ASSERT_TRUE(good.read_line(line));
}

TEST_F(RotctldHamlib, BeyondMaxClientsTheNewcomerIsToldAndClosed) {
  start();
  // Eight hosts (one host alone gets at most net.max_per_address, 6), none
  // idle for net.idle_evict_s (availability_test shows the newcomer served
  // once one is).
  std::vector<std::unique_ptr<TcpClient>> clients;
  for (int i = 1; i <= 8; ++i) {
    clients.push_back(
        std::make_unique<TcpClient>(daemon->ports().rotctld, "127.0.0." + std::to_string(i)));
    ASSERT_EQ(clients.back()->ask("v SPEED\n"), "100");
  }
  TcpClient ninth(daemon->ports().rotctld, "127.0.0.9");
  std::string line;
  ASSERT_TRUE(ninth.read_line(line));
  EXPECT_EQ(line, "RPRT -9");
  EXPECT_TRUE(ninth.wait_closed());
  for (auto& c : clients) EXPECT_EQ(c->ask("v SPEED\n"), "100");
}

}  // namespace
}  // namespace rotord::testing
