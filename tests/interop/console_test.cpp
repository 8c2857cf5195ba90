// The rotord console (docs/protocols/console.md) through the real daemon:
// rotord serves it on the pseudo-terminal `--pty console:LINK` creates, and
// socat plays the terminal (as a user's screen or picocom would). Controller
// time is the test's (--clock manual), so the settings saver's quiet time is
// advanced, not slept.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "daemon_process.hpp"
#include "file_text.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

class ConsoleInterop : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = make_temp_dir("rotord-console");
    config = dir + "/settings.json";
    link = dir + "/console";
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "g5500", "--clock", "manual", "--config", config, "--pty", "console:" + link});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    ASSERT_TRUE(std::filesystem::is_symlink(link)) << daemon->output();
  }
  void TearDown() override {
    daemon.reset();
    if (!dir.empty()) std::filesystem::remove_all(dir);
  }

  /// Types `lines` (LF-ended) into the console like a terminal program and
  /// returns what came back until `last` replies have ended (each reply's
  /// last line starts with "ok" or "error:"), bounded by socat's timeout.
  std::string type(const std::string& lines) {
    // printf's %b turns the \n escapes into line ends; single quotes keep the
    // shell off the rest (no test line holds a single quote).
    const CommandOutput r = run_command("printf '%b' '" + escape(lines) +
                                        "' | timeout 10 socat -t2 - " + link + ",raw,echo=0");
    return r.out;
  }
  static std::string escape(const std::string& text) {
    std::string out;
    for (char c : text) {
      if (c == '\n') {
        out += "\\n";
      } else if (c == '\\') {
        out += "\\\\";
      } else {
        out += c;
      }
    }
    return out;
  }
  std::string file_text() const { return read_file(config); }

  std::string dir, config, link;
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(ConsoleInterop, ConfiguresAndSavesThroughThePty) {
  const std::string out = type("get az.max_deg\nset park.az_deg 90\nget park.az_deg\nexport\n");
  EXPECT_EQ(out,
            "ok az.max_deg=450\r\n"
            "ok park.az_deg=90\r\n"
            "ok park.az_deg=90\r\n"
            "{\"settings_version\":2,\"park.az_deg\":90}\r\n"
            "ok 1 settings differ from the defaults\r\n");
  // Saved like every protocol's change, after 3 s without another one.
  ASSERT_GE(daemon->advance_ms(4000), 0);
  ASSERT_TRUE(daemon->wait_for_output("settings saved")) << daemon->output();
  EXPECT_NE(file_text().find("\"park.az_deg\": 90"), std::string::npos) << file_text();
  // Imported back all or nothing: one bad value changes nothing.
  const std::string bad = type("import {\"park.az_deg\": 10, \"az.max_deg\": 9999}\n");
  EXPECT_NE(bad.find("\r\nerror: nothing changed: "), std::string::npos) << bad;
  EXPECT_EQ(type("get park.az_deg\n"), "ok park.az_deg=90\r\n");
  EXPECT_EQ(type("import {\"park.az_deg\": 10}\n"), "ok 1 settings changed\r\n");
}

TEST_F(ConsoleInterop, ErrorsAreClearAndNothingMoves) {
  const std::string out = type("frobnicate\n" + std::string(700, 'x') +
                               "\nset access.serial_control false\nbootsel\nstatus\n");
  std::istringstream lines(out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "error: unknown command 'frobnicate' (help lists the commands)\r");
  std::getline(lines, line);
  EXPECT_EQ(line, "error: line too long (at most 512 bytes)\r");
  std::getline(lines, line);
  EXPECT_EQ(line, "error: access.serial_control is set through the web only\r");
  std::getline(lines, line);
  EXPECT_EQ(line.rfind("error: bootsel is for the Pico", 0), 0u) << line;
  std::getline(lines, line);
  EXPECT_EQ(line, "rotord 0.1.0 (Linux)\r");
  EXPECT_NE(out.find("\r\naz position_deg="), std::string::npos) << out;
  EXPECT_NE(out.find("state=IDLE fault=NONE"), std::string::npos) << out;
  EXPECT_EQ(out.substr(out.size() - 4), "ok\r\n");
}

TEST_F(ConsoleInterop, ResetAndRebootFromTheConsole) {
  EXPECT_EQ(type("reset\n"), "ok stopped, faults cleared\r\n");
  EXPECT_EQ(type("reboot\n"), "ok rebooting\r\n");
  ASSERT_TRUE(daemon->wait_for_output("restarting the controller")) << daemon->output();
  // The pty stays; the new controller's console answers on it.
  EXPECT_EQ(type("get az.max_deg\n"), "ok az.max_deg=450\r\n");
}

TEST_F(ConsoleInterop, ALongListingArrivesWhole) {
  const std::string out = type("list\nget az.min_deg\n");
  EXPECT_NE(out.find("el.enabled=true\r\n"), std::string::npos);
  EXPECT_TRUE(out.ends_with(" settings\r\nok az.min_deg=0\r\n")) << out.substr(out.size() - 200);
  EXPECT_GT(out.size(), 4000u);
}

// The set-up commands over the pty (docs/commissioning.md): a model fills
// the settings, commissioning starts, reports and stops like any motion.
TEST_F(ConsoleInterop, SetupModelAndCommissionThroughThePty) {
  const std::string model = type("setup model yaesu-g5500\n");
  EXPECT_NE(model.find("az.max_deg=450 [Y1][Y2] 450 deg\r\n"), std::string::npos) << model;
  EXPECT_NE(model.find("ok Yaesu G-5500: 9 settings filled"), std::string::npos) << model;
  // A known bearing sets an absolute sensor's zero: the G-5500's pot has none.
  const std::string pot = type("commission az bearing 90\n");
  EXPECT_EQ(pot, "error: a pot has no zero: the ends step calibrates it\r\n") << pot;
  const std::string started = type("commission az all -1 451\n");
  EXPECT_EQ(started.rfind("ok commissioning az started", 0), 0u) << started;
  ASSERT_GE(daemon->advance_ms(3000), 0);
  const std::string running = type("commission status\n");
  EXPECT_NE(running.find("commission az state=running step=direction"), std::string::npos)
      << running;
  const std::string stopped = type("stop\ncommission status\n");
  EXPECT_NE(stopped.find("commission az state=aborted step=direction reason=STOP\r\n"),
            std::string::npos)
      << stopped;
}

}  // namespace
}  // namespace rotord::testing
