// Settings changed through a protocol survive a restart of rotord, as the web
// API's do: GS-232 O calibration and P45, WRC AZOFFSET, Easycomm CW and
// rotctld C, each over real TCP against the real daemon (simulated G-5500
// on a manual clock the test advances), restarted on the same --config file.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "file_text.hpp"

namespace rotord::testing {
namespace {

namespace fs = std::filesystem;

/// Reads from `c` until `text` has arrived (or 3 s of silence); returns all.
std::string read_until(TcpClient& c, const std::string& text) {
  std::string got;
  while (got.find(text) == std::string::npos) {
    const std::string more = c.recv_once(3000);
    if (more.empty()) break;
    got += more;
  }
  return got;
}

/// The azimuth in a GS-232B reply "AZ=aaa" (or -1).
int gs232_az(const std::string& reply) {
  const auto pos = reply.find("AZ=");
  return pos == std::string::npos ? -1 : std::atoi(reply.c_str() + pos + 3);
}

class ProtocolSettings : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("rotord-protocol-settings-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    config = dir / "settings.json";
  }
  void TearDown() override {
    daemon.reset();
    fs::remove_all(dir);
  }
  void start() {
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "g5500", "--clock", "manual", "--config", config.string()});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
  }
  /// SIGTERM (a pending change is saved on the way out), then a new daemon.
  void restart() {
    ASSERT_EQ(daemon->terminate(), 0) << daemon->output();
    daemon.reset();
    start();
  }
  /// rotctld's value of a settings key ("park.az_deg=180" -> "180").
  std::string get_conf(const std::string& key) {
    TcpClient c(daemon->ports().rotctld);
    const std::string line = c.ask("\\get_conf " + key + "\n");
    const auto eq = line.find('=');
    return eq == std::string::npos ? line : line.substr(eq + 1);
  }

  fs::path dir;
  fs::path config;
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(ProtocolSettings, Gs232OffsetCalibrationSurvivesARestart) {
  start();
  TcpClient c(daemon->ports().gs232);
  ASSERT_TRUE(c.connected());
  // Turn to 100 deg, then declare it the CCW stop (0): the pot's low
  // calibration point moves 100 deg away from the current reading.
  c.send("M100\r");
  read_until(c, "\r");
  int az = -1;
  for (int n = 0; n < 60 && az != 100; ++n) {
    ASSERT_GE(daemon->advance_ms(1000), 0);
    c.send("C\r");
    az = gs232_az(read_until(c, "\n"));
  }
  ASSERT_EQ(az, 100);
  ASSERT_GE(daemon->advance_ms(3000), 0);  // coast out
  c.send("O\r");
  EXPECT_NE(read_until(c, "?\r\n").find("are you sure?"), std::string::npos);
  c.send("Y\r");
  EXPECT_NE(read_until(c, "\n").find("Completed"), std::string::npos);
  // The axis follows the new calibration and latches no jump fault.
  ASSERT_GE(daemon->advance_ms(2000), 0);
  c.send("C\r");
  EXPECT_EQ(gs232_az(read_until(c, "\n")), 0);
  TcpClient wrc(daemon->ports().wrc);
  EXPECT_EQ(wrc.ask("FAULT?\n"), "OK FAULT AZ=NONE EL=NONE");
  const std::string lo_counts = get_conf("az.pot_cal_lo_counts");
  ASSERT_NE(lo_counts, "62");  // the default: the calibration did change it

  restart();
  EXPECT_EQ(get_conf("az.pot_cal_lo_counts"), lo_counts);
  EXPECT_EQ(get_conf("az.pot_cal_lo_deg"), "0");
}

TEST_F(ProtocolSettings, Gs232P45SurvivesARestart) {
  start();
  {
    TcpClient c(daemon->ports().gs232);
    c.send("P36\r");
    EXPECT_EQ(read_until(c, "\r"), "\r");
  }
  restart();
  EXPECT_EQ(get_conf("gs232.az_range"), "360");
  {
    TcpClient c(daemon->ports().gs232);
    c.send("P45\r");
    EXPECT_EQ(read_until(c, "\r"), "\r");
  }
  restart();
  EXPECT_EQ(get_conf("gs232.az_range"), "450");
}

TEST_F(ProtocolSettings, WrcAzOffsetIsSavedAfterAQuietTimeAndSurvivesAKill) {
  start();
  {
    TcpClient c(daemon->ports().wrc);
    EXPECT_EQ(c.ask("AZOFFSET 5\n"), "OK AZOFFSET 5.00");
  }
  // Saved by the daemon's loop on its own, with no shutdown to flush it: not
  // within the quiet time, but once it has passed.
  ASSERT_GE(daemon->advance_ms(1000), 0);
  EXPECT_EQ(read_file(config).find("az.offset_deg"), std::string::npos);
  ASSERT_GE(daemon->advance_ms(3000), 0);
  ASSERT_NE(read_file(config).find("\"az.offset_deg\": 5\n"), std::string::npos)
      << read_file(config);
  ::kill(daemon->pid(), SIGKILL);
  daemon.reset();
  start();
  TcpClient c(daemon->ports().wrc);
  EXPECT_EQ(c.ask("AZOFFSET?\n"), "OK AZOFFSET 5.00");
}

TEST_F(ProtocolSettings, EasycommConfigWriteSurvivesARestart) {
  start();
  {
    TcpClient c(daemon->ports().easycomm);
    c.send("CW7,123\n");
    EXPECT_EQ(c.ask("CR7\n"), "CR7,123");
  }
  restart();
  TcpClient c(daemon->ports().easycomm);
  EXPECT_EQ(c.ask("CR7\n"), "CR7,123");
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

TEST_F(ProtocolSettings, RotctldSetConfSurvivesARestart) {
  start();
  {
    TcpClient c(daemon->ports().rotctld);
    EXPECT_EQ(c.ask("C park.az_deg 180\n"), "RPRT 0");
    EXPECT_EQ(c.ask("C park.az_deg 181\n"), "RPRT 0");  // a burst: one write
  }
  ASSERT_GE(daemon->advance_ms(8000), 0);  // past the quiet time
  ASSERT_EQ(daemon->terminate(), 0);
  EXPECT_EQ(count(daemon->output(), "rotord: settings saved to"), 1) << daemon->output();
  daemon.reset();
  start();
  EXPECT_EQ(get_conf("park.az_deg"), "181");
}

TEST_F(ProtocolSettings, AChangeTheApiSavedIsNotWrittenAgain) {
  start();
  {
    TcpClient c(daemon->ports().web);
    const std::string body = R"({"park.az_deg": 90})";
    c.send(
        "POST /api/settings HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n"
        "Content-Type: application/json\r\nContent-Length: " +
        std::to_string(body.size()) + "\r\n\r\n" + body);
    c.wait_closed(5000);
  }
  ASSERT_NE(read_file(config).find("\"park.az_deg\": 90\n"), std::string::npos);
  ASSERT_GE(daemon->advance_ms(8000), 0);  // past the quiet time
  ASSERT_EQ(daemon->terminate(), 0);
  EXPECT_EQ(count(daemon->output(), "rotord: settings saved to"), 0) << daemon->output();
}

}  // namespace
}  // namespace rotord::testing
