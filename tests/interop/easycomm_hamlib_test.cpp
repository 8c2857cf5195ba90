// Hamlib's real Easycomm backends (rotctl -m 201/202/204, Debian libhamlib-utils
// 4.5.4) against a running rotord on the simulated G-5500 (az 0..450, el 0..180),
// over TCP (Hamlib opens TCP for serial models given a dotted address) and over
// the pseudo-terminal rotord creates. The WRC port shows the unwrapped truth.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "poll.hpp"
#include "shell.hpp"
#include "wrc_view.hpp"

namespace rotord::testing {
namespace {

double angle_error(double a, double b) {
  return std::fabs(std::remainder(a - b, 360.0));
}

class EasycommHamlib : public ::testing::Test {
 protected:
  void start(std::vector<std::string> extra = {}) {
    // The test owns controller time (--clock manual): it advances it instead
    // of sleeping, so a loaded machine changes nothing but the wall time.
    std::vector<std::string> args = {"--sim",  "g5500",       "--clock",
                                     "manual", "--seed-port", std::to_string(seed_port)};
    args.insert(args.end(), extra.begin(), extra.end());
    daemon = std::make_unique<DaemonProcess>(args);
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    tcp = "127.0.0.1:" + std::to_string(daemon->ports().easycomm);
  }

  CommandOutput rotctl(int model, const std::string& where, const std::string& commands) {
    return rotctl_once(model, where, commands);
  }
  /// Reads the position through Hamlib: {az, el}, or empty on failure.
  std::vector<double> position(int model, const std::string& where) {
    return rotctl_position(model, where);
  }

  /// Polls through Hamlib until the position is within 1.5 deg (generous
  /// wall-clock bound; nothing here asserts on time).
  std::vector<double> wait_for(int model, const std::string& where, double az, double el) {
    std::vector<double> p;
    for (int n = 0; n < 300; ++n) {
      p = position(model, where);
      if (p.size() == 2 && angle_error(p[0], az) <= 1.5 && std::fabs(p[1] - el) <= 1.5) break;
      daemon->advance_ms(500);
    }
    return p;
  }

  /// The WRC view of the rotator: the unwrapped azimuth and the motion flags.
  std::string wrc_state() { return rotord::testing::wrc_state(*daemon); }
  double wrc_field(const std::string& key) { return rotord::testing::wrc_field(*daemon, key); }
  double wrc_az() { return wrc_field("AZ"); }
  bool wait_until_still() { return rotord::testing::wait_until_still(*daemon); }

  int seed_port = free_port();
  std::unique_ptr<DaemonProcess> daemon;
  std::string tcp;
};

TEST_F(EasycommHamlib, Model202SetsAndReadsThePositionThroughTheOverlap) {
  start();
  const std::vector<double> first = position(202, tcp);
  ASSERT_EQ(first.size(), 2u) << rotctl(202, tcp, "p").out;
  ASSERT_EQ(rotctl(202, tcp, "P 350 30").rc, 0);
  std::vector<double> p = wait_for(202, tcp, 350, 30);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 350, 1.5);
  EXPECT_NEAR(p[1], 30, 1.5);
  ASSERT_TRUE(wait_until_still());
  // 30 from 350 is nearer through the overlap: the rotator ends at 390
  // unwrapped, and Easycomm reads it back as the compass bearing 30.
  ASSERT_EQ(rotctl(202, tcp, "P 30 45").rc, 0);
  p = wait_for(202, tcp, 30, 45);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 30, 1.5);
  EXPECT_NEAR(p[1], 45, 1.5);
  ASSERT_TRUE(wait_until_still());
  EXPECT_NEAR(wrc_az(), 390, 1.5) << wrc_state();
}

TEST_F(EasycommHamlib, Model202StopMoveParkReset) {
  start();
  // A long go-to, stopped on the way.
  ASSERT_EQ(rotctl(202, tcp, "P 10 0").rc, 0);
  daemon->advance_ms(1000);
  ASSERT_EQ(rotctl(202, tcp, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  const double stopped = wrc_az();
  EXPECT_GT(angle_error(stopped, 10), 5) << wrc_state();
  daemon->advance_ms(1000);
  EXPECT_NEAR(wrc_az(), stopped, 0.5);  // it stays stopped
  // Move right (MR), then stop.
  ASSERT_EQ(rotctl(202, tcp, "M 16 50").rc, 0);
  daemon->advance_ms(1000);
  EXPECT_NE(wrc_state().find("FLAGS=CW"), std::string::npos) << wrc_state();
  ASSERT_EQ(rotctl(202, tcp, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  EXPECT_GT(wrc_az(), stopped);
  // Move up (MU), stop.
  ASSERT_EQ(rotctl(202, tcp, "M 2 50").rc, 0);
  daemon->advance_ms(1000);
  EXPECT_NE(wrc_state().find("UP"), std::string::npos) << wrc_state();
  ASSERT_EQ(rotctl(202, tcp, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  // Park: the default park position is az 0, el 0.
  ASSERT_EQ(rotctl(202, tcp, "K").rc, 0);
  const std::vector<double> p = wait_for(202, tcp, 0, 0);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_LE(angle_error(p[0], 0), 1.5);
  EXPECT_NEAR(p[1], 0, 1.5);
  EXPECT_EQ(rotctl(202, tcp, "R 1").rc, 0);
  EXPECT_EQ(rotctl(202, tcp, "_").out, "EasycommII\n");
}

TEST_F(EasycommHamlib, Model204MovesWithSpeedsAndParks) {
  start();
  ASSERT_EQ(position(204, tcp).size(), 2u);
  // VL4900: left (CCW) at speed 50.
  ASSERT_EQ(rotctl(204, tcp, "M 8 50").rc, 0);
  daemon->advance_ms(1000);
  EXPECT_NE(wrc_state().find("FLAGS=CCW"), std::string::npos) << wrc_state();
  ASSERT_EQ(rotctl(204, tcp, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  // V SPEED then M with speed -1 (VR1234), and up at full speed (VU9900).
  ASSERT_EQ(rotctl(204, tcp, "V SPEED 1234 M 16 -1").rc, 0);
  daemon->advance_ms(4000);  // the stop's settle and the reversal's dead time first
  EXPECT_NE(wrc_state().find("FLAGS=CW"), std::string::npos) << wrc_state();
  ASSERT_EQ(rotctl(204, tcp, "M 2 100").rc, 0);
  daemon->advance_ms(1000);
  EXPECT_NE(wrc_state().find("UP"), std::string::npos) << wrc_state();
  ASSERT_EQ(rotctl(204, tcp, "S").rc, 0);
  ASSERT_TRUE(wait_until_still());
  ASSERT_EQ(rotctl(204, tcp, "P 100 20").rc, 0);
  std::vector<double> p = wait_for(204, tcp, 100, 20);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 100, 1.5);
  ASSERT_EQ(rotctl(204, tcp, "K").rc, 0);
  p = wait_for(204, tcp, 0, 0);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[1], 0, 1.5);
  EXPECT_EQ(rotctl(204, tcp, "_").out, "EasycommIII\n");
}

TEST_F(EasycommHamlib, Model201SendsEasycommOneLines) {
  start();
  // 201 cannot read the position; the WRC port shows where it went.
  ASSERT_EQ(rotctl(201, tcp, "P 200 10").rc, 0);
  daemon->advance_ms(1000);
  ASSERT_TRUE(wait_until_still());
  EXPECT_NEAR(wrc_az(), 200, 1.5) << wrc_state();
  EXPECT_NEAR(wrc_field("EL"), 10, 1.5) << wrc_state();
}

TEST_F(EasycommHamlib, BadInputOverTcpGetsAlarmsAndMovesNothing) {
  start();
  TcpClient c(daemon->ports().easycomm);
  const std::string before = c.ask("AZ EL \n");
  ASSERT_EQ(before.rfind("AZ", 0), 0u) << before;
  EXPECT_EQ(c.ask("AZ500.0 EL10.0\n"), "ALRANGE");
  EXPECT_EQ(c.ask("AZ10.0EL10.0\n"), "ALSYNTAX");
  EXPECT_EQ(c.ask("FOO BAR\n"), "ALUNKNOWN");
  EXPECT_EQ(c.ask(std::string("\0\xff\x01garbage\n", 11)), "ALUNKNOWN");
  EXPECT_EQ(c.ask(std::string(100000, 'A') + "\n"), "ALOVERFLOW");
  EXPECT_EQ(c.ask("VE\n").rfind("VErotord-", 0), 0u);
  daemon->advance_ms(1000);
  EXPECT_TRUE(wait_until_still());
  // The same place, give or take the simulated pot's noise.
  const std::vector<double> a = numbers_in(before.substr(2)),
                            b = numbers_in(c.ask("AZ\n").substr(2));
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  EXPECT_NEAR(a[0], b[0], 0.5);
}

TEST_F(EasycommHamlib, PtyServesRotctlAcrossReopensAndSocat) {
  const std::string dir = make_temp_dir("rotord-ec");
  const std::string link = dir + "/easycomm";
  start({"--pty", "easycomm:" + link});
  EXPECT_NE(daemon->output().find("Easycomm II/III on pty /dev/pts/"), std::string::npos)
      << daemon->output();
  ASSERT_TRUE(std::filesystem::is_symlink(link));
  // Each rotctl run opens and closes the pty: it must keep working.
  ASSERT_EQ(position(202, link).size(), 2u) << rotctl(202, link, "p").out;
  ASSERT_EQ(position(202, link).size(), 2u);
  ASSERT_EQ(rotctl(202, link, "P 100 20").rc, 0);
  const std::vector<double> p = wait_for(202, link, 100, 20);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 100, 1.5);
  EXPECT_NEAR(p[1], 20, 1.5);
  // A plain program that opens the path like a COM port.
  const CommandOutput s =
      run_command("printf 'AZ EL \\nVE\\n' | timeout 5 socat -t1 - " + link + ",raw,echo=0");
  EXPECT_EQ(s.out.rfind("AZ", 0), 0u) << s.out;
  EXPECT_NE(s.out.find(" EL"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("\nVErotord-"), std::string::npos) << s.out;
  // And rotctl once more after socat closed it.
  EXPECT_EQ(position(204, link).size(), 2u);
  daemon->terminate();
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link)));  // cleaned up
  std::filesystem::remove_all(dir);
}

/// A serial device stand-in: socat joins two ptys like a null-modem cable.
class NullModem {
 public:
  explicit NullModem(const std::string& dir) : a(dir + "/ttyA"), b(dir + "/ttyB") {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execlp("socat", "socat", ("pty,raw,echo=0,link=" + a).c_str(),
               ("pty,raw,echo=0,link=" + b).c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // socat, a real process, creates the links on its own time.
    poll_until([&] { return std::filesystem::exists(a) && std::filesystem::exists(b); },
               std::chrono::seconds(5), std::chrono::milliseconds(50));
  }
  ~NullModem() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  NullModem(const NullModem&) = delete;
  NullModem& operator=(const NullModem&) = delete;
  std::string a, b;

 private:
  pid_t pid_ = -1;
};

TEST_F(EasycommHamlib, SerialDeviceWithBaudRate) {
  const std::string dir = make_temp_dir("rotord-ec");
  NullModem cable(dir);
  ASSERT_TRUE(std::filesystem::exists(cable.a));
  start({"--serial", "easycomm:" + cable.a + ":19200"});
  EXPECT_NE(daemon->output().find("on serial " + cable.a + " at 19200 baud"), std::string::npos)
      << daemon->output();
  ASSERT_EQ(position(202, cable.b).size(), 2u) << rotctl(202, cable.b, "p").out;
  ASSERT_EQ(rotctl(202, cable.b, "P 250 10").rc, 0);
  const std::vector<double> p = wait_for(202, cable.b, 250, 10);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p[0], 250, 1.5);
  daemon->terminate();
  std::filesystem::remove_all(dir);
}

TEST_F(EasycommHamlib, BadSerialOptionsStopTheDaemonWithAMessage) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--pty", "nosuch"},
        std::vector<std::string>{"--serial", "easycomm:/dev/null:12345"},
        std::vector<std::string>{"--serial", "easycomm"},
        std::vector<std::string>{"--serial", "seed:/nonexistent/tty:9600"}}) {
    DaemonProcess d(args);
    EXPECT_FALSE(d.ready()) << args[1];
    EXPECT_NE(d.output().find("rotord: "), std::string::npos) << d.output();
  }
}

TEST_F(EasycommHamlib, SeedProtocolOverTcpAndPty) {
  const std::string dir = make_temp_dir("rotord-ec");
  start({"--pty", "seed:" + dir + "/seed"});
  TcpClient c(seed_port);
  ASSERT_TRUE(c.connected());
  EXPECT_EQ(c.ask("$R,cw\n"), "$ERR,DISABLED");
  EXPECT_EQ(c.ask("$S,60\n"), "$OK,S,60");
  EXPECT_EQ(c.ask("$E\n"), "$OK,E");
  EXPECT_EQ(c.ask("$R,cw\n"), "$OK,R,CW");
  daemon->advance_ms(1000);
  EXPECT_NE(c.ask("$Q\n").find(",60,E,CW,"), std::string::npos);
  EXPECT_EQ(c.ask("$D\n"), "$OK,D");
  EXPECT_TRUE(wait_until_still());
  EXPECT_EQ(c.ask("$X,1\n"), "$ERR,UNKNOWN");
  EXPECT_EQ(c.ask("hello\n"), "$ERR,SYNTAX");
  const CommandOutput s = run_command("printf '$Q\\n$E\\n$R,ccw\\n$D\\n' | timeout 5 socat -t1 - " +
                                      dir + "/seed,raw,echo=0");
  EXPECT_EQ(s.out.rfind("$Q,", 0), 0u) << s.out;
  EXPECT_NE(s.out.find("$OK,E\r\n$OK,R,CCW\r\n$OK,D\r\n"), std::string::npos) << s.out;
  daemon->terminate();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rotord::testing
