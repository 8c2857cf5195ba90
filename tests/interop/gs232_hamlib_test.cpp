// Hamlib's real Yaesu GS-232 backends (rotctl -m 601/602/603/611/612, Debian
// libhamlib-utils 4.5.4) against a running rotord on the simulated G-5500 (az
// 0..450, el 0..180), over TCP (Hamlib opens TCP for serial models given a
// dotted address) and over the pseudo-terminal rotord creates. The WRC port
// shows the unwrapped truth and the motion flags.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "shell.hpp"
#include "wrc_view.hpp"

namespace rotord::testing {
namespace {

class Gs232Hamlib : public ::testing::Test {
 protected:
  /// Starts rotord with gs232.variant and gs232.ack_writes from a settings file.
  void start(char variant, bool ack_writes = true, std::vector<std::string> extra = {}) {
    dir = make_temp_dir("rotord-gs232");
    const std::string config = dir + "/settings.json";
    std::ofstream(config) << "{\"gs232.variant\": \"" << variant
                          << "\", \"gs232.ack_writes\": " << (ack_writes ? "true" : "false")
                          << "}\n";
    // The test owns controller time (--clock manual): it advances it instead
    // of sleeping, so a loaded machine changes nothing but the wall time.
    std::vector<std::string> args = {"--sim", "g5500", "--clock", "manual", "--config", config};
    args.insert(args.end(), extra.begin(), extra.end());
    daemon = std::make_unique<DaemonProcess>(args);
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    tcp = "127.0.0.1:" + std::to_string(daemon->ports().gs232);
  }
  void TearDown() override {
    daemon.reset();
    if (!dir.empty()) std::filesystem::remove_all(dir);
  }

  CommandOutput rotctl(int model, const std::string& commands, const std::string& where = "") {
    return rotctl_once(model, where.empty() ? tcp : where, commands);
  }
  /// Reads the position through Hamlib: {az, el}, or empty on failure.
  std::vector<double> position(int model, const std::string& where = "") {
    return rotctl_position(model, where.empty() ? tcp : where);
  }

  /// Polls through Hamlib until the position is within 1.5 deg (generous
  /// wall-clock bound; nothing here asserts on time).
  std::vector<double> wait_for(int model, double az, double el, const std::string& where = "") {
    std::vector<double> p;
    for (int n = 0; n < 300; ++n) {
      p = position(model, where);
      if (p.size() == 2 && std::fabs(p[0] - az) <= 1.5 && std::fabs(p[1] - el) <= 1.5) break;
      daemon->advance_ms(500);
    }
    return p;
  }

  std::string wrc_state() { return rotord::testing::wrc_state(*daemon); }
  double wrc_field(const std::string& key) { return rotord::testing::wrc_field(*daemon, key); }
  bool wait_until_still() { return rotord::testing::wait_until_still(*daemon); }
  /// Waits until the WRC flags show `flag` (a manual turn has started).
  bool wait_for_flag(const std::string& flag) {
    for (int n = 0; n < 100; ++n) {
      if (wrc_state().find(flag) != std::string::npos) return true;
      daemon->advance_ms(500);
    }
    return false;
  }

  std::string dir;
  std::unique_ptr<DaemonProcess> daemon;
  std::string tcp;
};

TEST_F(Gs232Hamlib, Model603SetsAndReadsThePositionThroughTheOverlap) {
  start('B');
  ASSERT_EQ(position(603).size(), 2u) << rotctl(603, "p").out;
  // Hamlib sends -10 as W350 030.
  ASSERT_EQ(rotctl(603, "P -10 30").rc, 0);
  std::vector<double> p = wait_for(603, 350, 30);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 350, 1.5);
  EXPECT_NEAR(p[1], 30, 1.5);
  ASSERT_TRUE(wait_until_still());
  // Into the overlap: W400 170 turns on to 400 (el over the zenith) and C2
  // reports AZ=400, as a GS-232B in P45 mode does.
  ASSERT_EQ(rotctl(603, "P 400 170").rc, 0);
  p = wait_for(603, 400, 170);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 400, 1.5);
  EXPECT_NEAR(p[1], 170, 1.5);
  ASSERT_TRUE(wait_until_still());
  EXPECT_NEAR(wrc_field("AZ"), 400, 1.5) << wrc_state();
  // And back out: W010 turns back to 10 on the dial, not on to 370.
  ASSERT_EQ(rotctl(603, "P 10 20").rc, 0);
  p = wait_for(603, 10, 20);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 10, 1.5);
  ASSERT_TRUE(wait_until_still());
  EXPECT_NEAR(wrc_field("AZ"), 10, 1.5) << wrc_state();
}

TEST_F(Gs232Hamlib, Model601SetsAndReadsThePositionThroughTheOverlap) {
  start('A');
  ASSERT_EQ(position(601).size(), 2u) << rotctl(601, "p").out;
  ASSERT_EQ(rotctl(601, "P 123.6 44.4").rc, 0);  // sent as W124 044
  std::vector<double> p = wait_for(601, 124, 44);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 124, 1.5);
  EXPECT_NEAR(p[1], 44, 1.5);
  ASSERT_EQ(rotctl(601, "P 450 180").rc, 0);
  p = wait_for(601, 450, 180);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 450, 1.5);
  EXPECT_NEAR(p[1], 180, 1.5);
  ASSERT_TRUE(wait_until_still());
  EXPECT_NEAR(wrc_field("AZ"), 450, 1.5) << wrc_state();
}

TEST_F(Gs232Hamlib, Model603StopsAndMovesWithSpeeds) {
  start('B');
  // A long go-to, stopped on the way.
  ASSERT_EQ(rotctl(603, "P 440 0").rc, 0);
  ASSERT_TRUE(wait_for_flag("FLAGS=CW"));
  ASSERT_EQ(rotctl(603, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  const double stopped = wrc_field("AZ");
  EXPECT_LT(stopped, 430) << wrc_state();
  daemon->advance_ms(1000);
  EXPECT_NEAR(wrc_field("AZ"), stopped, 0.5);  // it stays stopped
  // M 8 50 sends X2 and L: counter-clockwise at the second speed step.
  ASSERT_EQ(rotctl(603, "M 8 50").rc, 0);
  ASSERT_TRUE(wait_for_flag("FLAGS=CCW")) << wrc_state();
  EXPECT_EQ(wrc_field("SPEED"), 50);
  daemon->advance_ms(1000);  // a second of turning before the stop
  ASSERT_EQ(rotctl(603, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  EXPECT_LT(wrc_field("AZ"), stopped);
  // M 16 100: X4 and R.
  ASSERT_EQ(rotctl(603, "M 16 100").rc, 0);
  ASSERT_TRUE(wait_for_flag("FLAGS=CW")) << wrc_state();
  EXPECT_EQ(wrc_field("SPEED"), 100);
  ASSERT_EQ(rotctl(603, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  // M 2 1: X1 and U; M 4 70: X3 and D.
  ASSERT_EQ(rotctl(603, "M 2 1").rc, 0);
  ASSERT_TRUE(wait_for_flag("UP")) << wrc_state();
  EXPECT_EQ(wrc_field("SPEED"), 25);
  // Up far enough that DOWN below is not refused at the lower end stop (a
  // loaded machine may take longer than the rotctl round trip to get there).
  for (int n = 0; n < 100 && wrc_field("EL") < 3.0; ++n) daemon->advance_ms(500);
  EXPECT_GE(wrc_field("EL"), 3.0) << wrc_state();
  ASSERT_EQ(rotctl(603, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  ASSERT_EQ(rotctl(603, "M 4 70").rc, 0);
  ASSERT_TRUE(wait_for_flag("DOWN")) << wrc_state();
  EXPECT_EQ(wrc_field("SPEED"), 75);
  ASSERT_EQ(rotctl(603, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  EXPECT_EQ(position(603).size(), 2u);
}

TEST_F(Gs232Hamlib, ParkAndResetAreNotOfferedByTheGs232Backends) {
  // None of Hamlib's GS-232 backends has park or reset: the client refuses
  // them itself and nothing reaches the rotator.
  start('B');
  ASSERT_TRUE(wait_until_still());
  const double az = wrc_field("AZ");
  for (int model : {601, 603}) {
    const CommandOutput k = rotctl(model, "K");
    EXPECT_NE(k.rc, 0);
    EXPECT_NE(k.out.find("Feature not available"), std::string::npos) << k.out;
  }
  daemon->advance_ms(1000);
  EXPECT_NEAR(wrc_field("AZ"), az, 0.5);
}

TEST_F(Gs232Hamlib, Model601MovesWithSpeedAndStops) {
  start('A');
  ASSERT_EQ(rotctl(601, "M 16 50").rc, 0);  // X2, R
  ASSERT_TRUE(wait_for_flag("FLAGS=CW")) << wrc_state();
  EXPECT_EQ(wrc_field("SPEED"), 50);
  ASSERT_EQ(rotctl(601, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  EXPECT_EQ(position(601).size(), 2u);
}

TEST_F(Gs232Hamlib, Model602GenericNeedsNoAcknowledgements) {
  // 602 writes the next command at once after W / S: with gs232.ack_writes
  // off, every C2 read gets the position, never a stray CR.
  start('A', false);
  for (int n = 0; n < 10; ++n) {
    const CommandOutput r = rotctl(602, "P 200 20 p S p");
    const std::vector<double> v = numbers_in(r.out);
    ASSERT_EQ(v.size(), 4u) << r.out;
    EXPECT_GT(v[0], 1.0) << r.out;  // a misread reply leaves 0.00
    EXPECT_GT(v[2], 1.0) << r.out;
  }
  ASSERT_EQ(rotctl(602, "P 200 20").rc, 0);
  const std::vector<double> p = wait_for(602, 200, 20);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 200, 1.5);
  EXPECT_NEAR(p[1], 20, 1.5);
}

TEST_F(Gs232Hamlib, Models611And612AzimuthAndElevationOnly) {
  start('B');
  // 611 sends W120 000 and reads C2; a non-zero elevation it refuses itself.
  ASSERT_EQ(rotctl(611, "P 120 0").rc, 0);
  std::vector<double> p = wait_for(611, 120, 0);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 120, 1.5);
  EXPECT_NE(rotctl(611, "P 120 20").rc, 0);
  // 612 sends W000 040: the azimuth goes to 0 as on the real controller.
  ASSERT_EQ(rotctl(612, "P 0 40").rc, 0);
  p = wait_for(612, 0, 40);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[1], 40, 1.5);
}

TEST_F(Gs232Hamlib, BadInputOverTcpGetsTheErrorPromptAndMovesNothing) {
  start('B');
  ASSERT_TRUE(wait_until_still());
  TcpClient c(daemon->ports().gs232);
  ASSERT_TRUE(c.connected());
  const std::string before = c.ask("C2\r");
  ASSERT_EQ(before.rfind("AZ=", 0), 0u) << before;
  EXPECT_EQ(c.ask("W500 010\r"), "?>");
  EXPECT_EQ(c.ask("W100 200\r"), "?>");
  EXPECT_EQ(c.ask("M-10\r"), "?>");
  EXPECT_EQ(c.ask("Q\r"), "?>");
  EXPECT_EQ(c.ask(std::string("\0\xff\x01garbage\r", 11)), "?>");
  EXPECT_EQ(c.ask(std::string(100000, 'M') + "\r"), "?>");
  EXPECT_EQ(c.ask("\r\r\rC2\r"), before);  // empty commands: no reply
  daemon->advance_ms(1000);
  EXPECT_TRUE(wait_until_still());
  EXPECT_EQ(c.ask("C2\r"), before);
  // A write-only command answers a bare CR at once, in one segment.
  ASSERT_TRUE(c.send("X4\r"));
  EXPECT_EQ(c.recv_once(), "\r");
}

TEST_F(Gs232Hamlib, TimedListOverTcp) {
  start('B');
  TcpClient c(daemon->ports().gs232);
  ASSERT_TRUE(c.send("W002 100 010 110 020\r"));
  EXPECT_EQ(c.recv_once(), "\r");
  EXPECT_EQ(c.ask("N\r"), "+0001+0002");
  ASSERT_TRUE(c.send("T\r"));
  EXPECT_EQ(c.recv_once(), "\r");
  std::string n;
  for (int k = 0; k < 100 && n != "+0002+0002"; ++k) {
    n = c.ask("N\r");
    daemon->advance_ms(500);
  }
  EXPECT_EQ(n, "+0002+0002");
  const std::vector<double> p = wait_for(603, 110, 20);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 110, 1.5);
  EXPECT_NEAR(p[1], 20, 1.5);
}

TEST_F(Gs232Hamlib, PtyServesRotctlAndAPlainTerminalProgram) {
  const std::string pty_dir = make_temp_dir("rotord-gs232");
  const std::string link = pty_dir + "/gs232";
  start('B', true, {"--pty", "gs232:" + link});
  ASSERT_TRUE(std::filesystem::is_symlink(link)) << daemon->output();
  ASSERT_EQ(position(603, link).size(), 2u) << rotctl(603, "p", link).out;
  ASSERT_EQ(rotctl(603, "P 100 20", link).rc, 0);
  const std::vector<double> p = wait_for(603, 100, 20, link);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 100, 1.5);
  EXPECT_NEAR(p[1], 20, 1.5);
  // A terminal program typing commands, as the manual's installer does.
  const CommandOutput s =
      run_command("printf 'C2\\rX9\\rH3\\r' | timeout 5 socat -t1 - " + link + ",raw,echo=0");
  // (After a leftover CR: rotctl exits without reading the one for its W.)
  EXPECT_EQ(s.out.find_first_not_of("\r\n"), s.out.find("AZ=")) << s.out;
  EXPECT_NE(s.out.find("\r\n?>\r\n---------- COMMAND LIST 3"), std::string::npos) << s.out;
  EXPECT_EQ(position(601, link).size(), 0u);  // the B format is not the A's
  EXPECT_EQ(position(603, link).size(), 2u);
  daemon->terminate();
  std::filesystem::remove_all(pty_dir);
}

}  // namespace
}  // namespace rotord::testing
