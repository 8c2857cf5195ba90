// Web and REST access control through the real daemon and curl (issue 12):
// off by default, on with one call; without credentials only STOP and the
// login page answer; the session cookie's flags; bearer tokens, a read-only
// one refused a go-to; the control lock binding Hamlib's rotctl; the
// password and tokens kept only as hashes across a restart.
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

class WebAuth : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = make_temp_dir("rotord-auth");
    config = dir + "/settings.json";
    start();
  }
  void TearDown() override {
    daemon.reset();
    std::filesystem::remove_all(dir);
  }
  void start() {
    daemon.reset();
    daemon = std::make_unique<DaemonProcess>(
        std::vector<std::string>{"--sim", "g5500", "--clock", "manual", "--config", config});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    base = "http://127.0.0.1:" + std::to_string(daemon->ports().web);
  }
  int status(const std::string& args) { return status_of(curl(args)); }
  /// "-H 'Authorization: Bearer rtd_...'" for a new token.
  std::string token(const std::string& name, const std::string& scope) {
    const std::string r = curl("-b " + jar + " --json '{\"name\":\"" + name + "\",\"scope\":\"" +
                               scope + "\"}' " + base + "/api/tokens");
    EXPECT_EQ(status_of(r), 201) << r;
    const auto at = r.find("rtd_");
    return at == std::string::npos ? "" : "-H 'Authorization: Bearer " + r.substr(at, 36) + "'";
  }
  void turn_on() {
    const std::string r = curl("-c " + jar + " --json '{\"password\":\"" + std::string(kPassword) +
                               "\"}' " + base + "/api/password");
    ASSERT_EQ(status_of(r), 200) << r;
  }
  std::string dir, config, base;
  std::string jar = "";
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(WebAuth, CurlWithAndWithoutCredentialsAndStopForEveryone) {
  jar = dir + "/jar";
  EXPECT_EQ(status(base + "/api/status"), 200);  // off by default
  turn_on();
  EXPECT_EQ(status(base + "/api/status"), 401);
  EXPECT_EQ(status("--json '{\"az\": 200}' " + base + "/api/goto"), 401);
  EXPECT_EQ(status("-X POST " + base + "/api/stop"), 200);  // STOP needs nothing
  EXPECT_EQ(status(base + "/login.html"), 200);
  const std::string page = curl(base + "/");
  EXPECT_EQ(status_of(page), 303);
  EXPECT_NE(page.find("Location: /login.html"), std::string::npos) << page;
  EXPECT_EQ(status("-b " + jar + " " + base + "/api/status"), 200);

  // A login from curl: the cookie's flags.
  const std::string jar2 = dir + "/jar2";
  EXPECT_EQ(status("--json '{\"password\":\"wrong one\"}' " + base + "/api/login"), 401);
  const std::string login = curl("-c " + jar2 + " --json '{\"password\":\"" +
                                 std::string(kPassword) + "\"}' " + base + "/api/login");
  EXPECT_EQ(status_of(login), 200) << login;
  EXPECT_NE(login.find("; HttpOnly"), std::string::npos) << login;
  EXPECT_NE(login.find("; SameSite=Strict"), std::string::npos) << login;
  EXPECT_EQ(status("-b " + jar2 + " --json '{\"az\": 200}' " + base + "/api/goto"), 200);
  // Logged out: the cookie is dead.
  EXPECT_EQ(status("-b " + jar2 + " --json '{}' " + base + "/api/logout"), 200);
  EXPECT_EQ(status("-b " + jar2 + " " + base + "/api/status"), 401);
  daemon->advance_ms(10);  // reads what the daemon printed meanwhile
  EXPECT_NE(daemon->output().find("failed web login from 127.0.0.1"), std::string::npos)
      << daemon->output();
}

TEST_F(WebAuth, ReadOnlyTokenIsRefusedAGotoAControlTokenIsNot) {
  jar = dir + "/jar";
  turn_on();
  const std::string reader = token("logger", "read");
  const std::string driver = token("tracker", "control");
  EXPECT_EQ(status(reader + " " + base + "/api/status"), 200);
  EXPECT_EQ(status(reader + " --json '{\"az\": 200}' " + base + "/api/goto"), 403);
  EXPECT_EQ(status(reader + " -X POST " + base + "/api/stop"), 200);
  EXPECT_EQ(status(driver + " --json '{\"az\": 200}' " + base + "/api/goto"), 200);
  EXPECT_EQ(status("-H 'Authorization: Bearer rtd_0123456789abcdef0123456789abcdef' " + base +
                   "/api/status"),
            401);
  // Never read back: the settings show masks, the file holds hashes only.
  const std::string doc = curl("-b " + jar + " " + base + "/api/settings");
  EXPECT_NE(doc.find("\"web.password\":\"********\""), std::string::npos) << doc;
  EXPECT_EQ(doc.find("rtd_"), std::string::npos);
  EXPECT_EQ(doc.find("pbkdf2"), std::string::npos);
  daemon->terminate();
  std::stringstream file;
  file << std::ifstream(config).rdbuf();
  EXPECT_NE(file.str().find("pbkdf2-sha256$100000$"), std::string::npos) << file.str();
  EXPECT_EQ(file.str().find(kPassword), std::string::npos);
  EXPECT_EQ(file.str().find("rtd_"), std::string::npos);
  // After a restart: the token still works, the old login does not.
  start();
  EXPECT_EQ(status(driver + " --json '{\"az\": 100}' " + base + "/api/goto"), 200);
  EXPECT_EQ(status("-b " + jar + " " + base + "/api/status"), 401);
}

TEST_F(WebAuth, MetricsNeedAReadTokenOnceAccessControlIsOnAndPromtoolReadsThem) {
  jar = dir + "/jar";
  EXPECT_EQ(status(base + "/metrics"), 200);  // off by default
  turn_on();
  const std::string reader = token("prometheus", "read");
  // Positions, targets and connections are not for strangers; health is.
  EXPECT_EQ(status(base + "/metrics"), 401);
  EXPECT_EQ(status(base + "/healthz"), 200);
  EXPECT_EQ(status("--json '{\"password\":\"wrong one\"}' " + base + "/api/login"), 401);
  const CommandOutput scrape = run_command("timeout 20 curl -s " + reader + " " + base +
                                           "/metrics | promtool check metrics");
  EXPECT_EQ(scrape.rc, 0) << scrape.out;
  // The failed login is counted as an HTTP auth failure.
  const std::string page = curl(reader + " " + base + "/metrics");
  EXPECT_NE(page.find("rotord_auth_failures_total{protocol=\"http\"} "), std::string::npos);
  EXPECT_EQ(page.find("rotord_auth_failures_total{protocol=\"http\"} 0\n"), std::string::npos)
      << page;
}

TEST_F(WebAuth, TheControlLockBindsRotctlUntilReleased) {
  jar = dir + "/jar";
  turn_on();
  const std::string driver = token("tracker", "control");
  const std::string rotctl =
      "timeout 20 rotctl -m 2 -r 127.0.0.1:" + std::to_string(daemon->ports().rotctld) + " ";
  ASSERT_EQ(run_command(rotctl + "P 100 10 2>&1").rc, 0);
  const std::string locked = curl(driver + " --json '{\"minutes\": 5}' " + base + "/api/lock");
  ASSERT_EQ(status_of(locked), 200) << locked;
  const CommandOutput refused = run_command(rotctl + "P 120 10 2>&1");
  EXPECT_NE(refused.rc, 0) << refused.out;
  EXPECT_NE(refused.out.find("Command rejected"), std::string::npos) << refused.out;
  EXPECT_EQ(run_command(rotctl + "p 2>&1").rc, 0);  // reading is fine
  EXPECT_EQ(run_command(rotctl + "S 2>&1").rc, 0);  // and STOP
  EXPECT_EQ(status("-b " + jar + " --json '{\"az\": 200}' " + base + "/api/goto"), 423);
  EXPECT_EQ(status("-X POST " + base + "/api/stop"), 200);
  EXPECT_EQ(status(driver + " --json '{}' " + base + "/api/unlock"), 200);
  EXPECT_EQ(run_command(rotctl + "P 120 10 2>&1").rc, 0);
}

}  // namespace
}  // namespace rotord::testing
