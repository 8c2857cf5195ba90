// Access control never fails open (issue 29, item 5), through the real daemon:
// a settings file with a password and access.control_networks set, damaged
// in every way a file gets damaged (a bad value, an unknown key, a wrong
// type, an access setting that does not read, a truncated file). Every valid
// value is kept and the bad one named in the log and on the settings page;
// when the access settings themselves cannot be read, every port obeys only
// STOP and answers status until the file is fixed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

constexpr const char* kPassword = "correct horse battery";
constexpr const char* kStranger = "127.0.0.5";

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class FailClosed : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = make_temp_dir("rotord-failclosed");
    config = dir + "/settings.json";
    jar = dir + "/jar";
    // The owner's setup: a password, the allow-list, a park position.
    start();
    ASSERT_EQ(status_of(curl("-c " + jar + " --json '{\"password\":\"" + kPassword + "\"}' " +
                             base + "/api/password")),
              200);
    ASSERT_EQ(status_of(curl("-b " + jar +
                             " --json '{\"access.control_networks\": \"127.0.0.1/32\", "
                             "\"park.az_deg\": 77}' " +
                             base + "/api/settings")),
              200);
    daemon.reset();
    good = read_file(config);
    ASSERT_NE(good.find("pbkdf2-sha256$"), std::string::npos) << good;
    ASSERT_NE(good.find("\"access.control_networks\": \"127.0.0.1/32\""), std::string::npos);
  }
  void TearDown() override {
    daemon.reset();
    std::filesystem::remove_all(dir);
  }
  void start() {
    daemon = std::make_unique<DaemonProcess>(
        std::vector<std::string>{"--sim", "g5500", "--clock", "manual", "--config", config});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    base = "http://127.0.0.1:" + std::to_string(daemon->ports().web);
  }
  /// The good file with `member` added after its first line.
  std::string with_member(const std::string& member) {
    const auto at = good.find('\n');
    return good.substr(0, at + 1) + "  " + member + ",\n" + good.substr(at + 1);
  }
  void start_with(const std::string& document) {
    std::ofstream(config, std::ios::trunc) << document;
    start();
    daemon->advance_ms(10);  // reads what the daemon printed
  }
  void log_in() {
    ASSERT_EQ(status_of(curl("-c " + jar + " --json '{\"password\":\"" + kPassword + "\"}' " +
                             base + "/api/login")),
              200);
  }
  bool has_target() {
    const std::string s = curl("-b " + jar + " " + base + "/api/status");
    return s.find("\"target_deg\":null") == std::string::npos;
  }
  /// A stranger and the owner over WRC: what `AZ 100` and `STOP` get.
  void expect_wrc(const std::string& from, const std::string& move_reply) {
    TcpClient wrc(daemon->ports().wrc, from);
    EXPECT_EQ(wrc.ask("AZ 100\n"), move_reply) << from;
    EXPECT_EQ(wrc.ask("STOP\n"), "OK STOP") << from;
  }
  /// The settings page's report: GET /api/status settings_load.
  std::string load_report() {
    const std::string s = curl("-b " + jar + " " + base + "/api/status");
    const auto at = s.find("\"settings_load\":");
    return at == std::string::npos ? "" : s.substr(at, s.find(']', at) - at + 1);
  }

  std::string dir, config, jar, base, good;
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(FailClosed, ABadValueUnknownKeyOrWrongTypeElsewhereKeepsTheAccessSettings) {
  const struct {
    const char* member;
    const char* key;
  } cases[] = {
      {R"("az.max_deg": 99999)", "az.max_deg"},          // the issue's own example
      {R"("az.offset": 1)", "az.offset"},                // an unknown (hand-edited) key
      {R"("el.max_deg": "straight up")", "el.max_deg"},  // a wrong type
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.member);
    start_with(with_member(c.member));
    EXPECT_NE(daemon->output().find(std::string(c.key) + ": "), std::string::npos)
        << daemon->output();
    // The password and the allow-list are in force: a stranger reads nothing
    // on the web and cannot move; the owner can.
    EXPECT_EQ(http_from(kStranger, daemon->ports().web, "GET", "/api/settings").status, 401);
    expect_wrc(kStranger, "ERROR NOT ALLOWED");
    daemon->advance_ms(1000);
    log_in();
    EXPECT_FALSE(has_target());
    expect_wrc("127.0.0.1", "OK AZ 100.00");
    // Every valid value kept; the bad one named on the settings page.
    EXPECT_NE(curl("-b " + jar + " " + base + "/api/settings").find("\"park.az_deg\":77"),
              std::string::npos);
    const std::string report = load_report();
    EXPECT_NE(report.find("\"access_unreadable\":false"), std::string::npos) << report;
    EXPECT_NE(report.find(std::string("\"key\":\"") + c.key + "\""), std::string::npos) << report;
    daemon.reset();
  }
}

TEST_F(FailClosed, UnreadableAccessSettingsLeaveOnlyStopAndStatusOnEveryPort) {
  const auto cut = good.find("\"web.password\"");
  ASSERT_NE(cut, std::string::npos);
  const struct {
    const char* what;
    std::string document;
  } cases[] = {
      {"a bad allow-list", with_member(R"("access.control_networks": "127.0.0.1/40")")},
      {"a wrong type", with_member(R"("access.serial_control": "maybe")")},
      {"an unknown access key", with_member(R"("access.control_network": "0.0.0.0/0")")},
      {"a truncated file", good.substr(0, cut + 30)},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    start_with(c.document);
    EXPECT_NE(daemon->output().find("the access settings cannot be read"), std::string::npos)
        << daemon->output();
    // Nobody moves anything, the owner's own address included, on every port.
    expect_wrc("127.0.0.1", "ERROR NOT ALLOWED");
    expect_wrc(kStranger, "ERROR NOT ALLOWED");
    TcpClient rotctld(daemon->ports().rotctld, kStranger);
    EXPECT_EQ(rotctld.ask("P 100 10\n"), "RPRT -9");
    EXPECT_EQ(rotctld.ask("S\n"), "RPRT 0");
    TcpClient easycomm(daemon->ports().easycomm);
    EXPECT_EQ(easycomm.ask("AZ100.0 EL10.0\n"), "ALDENIED");
    const HttpResponse go =
        http_from(kStranger, daemon->ports().web, "POST", "/api/goto", R"({"az": 100})");
    EXPECT_TRUE(go.status == 401 || go.status == 503) << go.status << " " << go.body;
    EXPECT_EQ(http_from(kStranger, daemon->ports().web, "POST", "/api/settings",
                        R"({"access.control_networks": ""})")
                      .status == 200,
              false);
    // STOP always; status is answered and says why.
    EXPECT_EQ(http_from(kStranger, daemon->ports().web, "POST", "/api/stop").status, 200);
    daemon->advance_ms(1000);
    const std::string status = http(daemon->ports().web, "GET", "/api/status").body;
    const bool password_read =
        status.empty() || status.find("\"settings_load\"") == std::string::npos;
    if (password_read) log_in();  // the password is in force: the owner logs in to see it
    EXPECT_FALSE(has_target());
    const std::string report = load_report();
    EXPECT_NE(report.find("\"access_unreadable\":true"), std::string::npos) << report;
    // A logged-in owner is refused too: the rules that allow it are unknown.
    if (password_read) {
      EXPECT_EQ(status_of(curl("-b " + jar + " --json '{\"az\": 100}' " + base + "/api/goto")),
                503);
    }
    // The valid values before the damage are kept.
    EXPECT_NE(curl("-b " + jar + " " + base + "/api/settings").find("\"park.az_deg\":77"),
              std::string::npos);
    // The file is left for the owner to fix.
    EXPECT_EQ(read_file(config), c.document);
    daemon.reset();
  }
  // Fixed: back to normal.
  start_with(good);
  EXPECT_EQ(daemon->output().find("the access settings cannot be read"), std::string::npos);
  expect_wrc("127.0.0.1", "OK AZ 100.00");
}

}  // namespace
}  // namespace rotord::testing
