// Access control through the real daemon and real clients (issue 12): a
// client outside access.control_networks reads but cannot move (Hamlib's
// rotctl -m 2), every line protocol answers it in its own way, STOP always
// works; a pty follows access.serial_control; the web refuses DNS
// rebinding and framing (curl).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

class AccessControl : public ::testing::Test {
 protected:
  void start(std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"--sim", "g5500", "--clock", "manual"};
    args.insert(args.end(), extra.begin(), extra.end());
    daemon = std::make_unique<DaemonProcess>(args);
    ASSERT_TRUE(daemon->ready()) << daemon->output();
  }
  /// Access settings go through the web (they are never line-writable).
  void set(const std::string& json) {
    const HttpResponse r = http(daemon->ports().web, "POST", "/api/settings", json);
    ASSERT_EQ(r.status, 200) << r.body;
  }
  CommandOutput rotctl(const std::string& commands) {
    return run_command("timeout 20 rotctl -m 2 -r 127.0.0.1:" +
                       std::to_string(daemon->ports().rotctld) + " " + commands + " 2>&1");
  }
  bool has_target() {
    const HttpResponse s = http(daemon->ports().web, "GET", "/api/status");
    return s.body.find("\"target_deg\":null") == std::string::npos;
  }
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(AccessControl, HamlibRotctlOutsideTheAllowListReadsButCannotMove) {
  start();
  set(R"({"access.control_networks": "10.0.0.0/8"})");  // the test runs on 127.0.0.1
  const CommandOutput read = rotctl("p");
  EXPECT_EQ(read.rc, 0) << read.out;
  const CommandOutput move = rotctl("P 100 10");
  EXPECT_NE(move.rc, 0) << move.out;
  EXPECT_NE(move.out.find("Command rejected"), std::string::npos) << move.out;
  EXPECT_EQ(rotctl("S").rc, 0);
  daemon->advance_ms(2000);
  EXPECT_FALSE(has_target());

  // Every line protocol says no in its own way, and stops.
  TcpClient wrc(daemon->ports().wrc), gs232(daemon->ports().gs232),
      easycomm(daemon->ports().easycomm);
  EXPECT_EQ(wrc.ask("AZ 200\n"), "ERROR NOT ALLOWED");
  EXPECT_EQ(wrc.ask("STOP\n"), "OK STOP");
  gs232.send("M200\r");
  std::string line;
  ASSERT_TRUE(gs232.read_line(line));
  EXPECT_EQ(line, "?>");
  EXPECT_EQ(easycomm.ask("AZ200.0 EL10.0\n"), "ALDENIED");
  EXPECT_EQ(easycomm.ask("CWwifi.password,attacker-pass\n"), "ALDENIED");
  daemon->advance_ms(2000);
  EXPECT_FALSE(has_target());

  // In the list: control.
  set(R"({"access.control_networks": "10.0.0.0/8, 127.0.0.0/8"})");
  EXPECT_EQ(rotctl("P 100 10").rc, 0);
  EXPECT_TRUE(has_target());
}

TEST_F(AccessControl, APtyFollowsTheSerialControlSetting) {
  const std::string dir = make_temp_dir("rotord-access");
  const std::string link = dir + "/easycomm";
  start({"--pty", "easycomm:" + link});
  set(R"({"access.serial_control": false})");
  const CommandOutput refused =
      run_command("printf 'MR\\nAZ EL\\n' | timeout 5 socat -t1 - " + link + ",raw,echo=0");
  EXPECT_NE(refused.out.find("ALDENIED"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("AZ"), std::string::npos) << refused.out;
  daemon->advance_ms(1000);
  const HttpResponse s = http(daemon->ports().web, "GET", "/api/status");
  EXPECT_NE(s.body.find("\"moving\":false"), std::string::npos) << s.body;
  std::filesystem::remove_all(dir);
}

TEST_F(AccessControl, TheWebRefusesDnsRebindingCrossSiteRequestsAndFraming) {
  start();
  const std::string base = "http://127.0.0.1:" + std::to_string(daemon->ports().web);
  auto curl = [&](const std::string& args) {
    return run_command("timeout 20 curl -s -i " + args + " 2>&1");
  };
  // After DNS rebinding the browser sends the attacker's name.
  const CommandOutput rebound =
      curl("-H 'Host: attacker.example:8080' --json '{\"az\": 200}' " + base + "/api/goto");
  EXPECT_NE(rebound.out.find("HTTP/1.1 421"), std::string::npos) << rebound.out;
  // A foreign page posting to the controller's own name.
  const CommandOutput cross =
      curl("-H 'Origin: http://evil.example' --json '{\"az\": 200}' " + base + "/api/goto");
  EXPECT_NE(cross.out.find("HTTP/1.1 403"), std::string::npos) << cross.out;
  daemon->advance_ms(1000);
  EXPECT_FALSE(has_target());
  // A name the operator added, e.g. a reverse proxy's.
  set(R"({"web.allowed_hosts": "rotor.example.org"})");
  EXPECT_NE(curl("-H 'Host: rotor.example.org' " + base + "/api/status").out.find("HTTP/1.1 200"),
            std::string::npos);
  // The page may not be framed by another site.
  const CommandOutput page = curl(base + "/");
  EXPECT_NE(page.out.find("X-Frame-Options: DENY"), std::string::npos) << page.out;
  EXPECT_NE(page.out.find("frame-ancestors 'none'"), std::string::npos) << page.out;
}

}  // namespace
}  // namespace rotord::testing
