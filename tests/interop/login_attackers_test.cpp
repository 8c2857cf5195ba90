// Password guessing from many addresses (issue 29, item 4), through the real
// daemon: wrong passwords from 16 rotating addresses, two in flight, for
// minutes of the network's clock (--clock manual advances it). Prints the
// guesses checked per minute in total, and the owner's logins during the
// attack: from a browser with its device cookie, and from an address on the
// allow-list.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

constexpr const char* kPassword = "correct horse battery";

class LoginAttackers : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = make_temp_dir("rotord-guess");
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "g5500", "--clock", "manual", "--config", dir + "/settings.json"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    web = daemon->ports().web;
    base = "http://127.0.0.1:" + std::to_string(web);
  }
  void TearDown() override {
    stop_attack();
    daemon.reset();
    std::filesystem::remove_all(dir);
  }
  std::string login_json() { return "--json '{\"password\":\"" + std::string(kPassword) + "\"}' "; }

  /// Two attackers, each rotating over 127.0.1.1-16, one guess after another.
  void start_attack() {
    for (int lane = 0; lane < 2; ++lane) {
      attackers.emplace_back([this, lane] {
        for (int n = lane; running; n += 2) {
          const std::string from = "127.0.1." + std::to_string(n % 16 + 1);
          const int s = http_from(from, web, "POST", "/api/login",
                                  R"({"password": "guess )" + std::to_string(n) + "\"}")
                            .status;
          if (s == 401) ++checked;
          if (s == 429) ++held_back;
          if (s == 503) ++busy;
        }
      });
    }
  }
  void stop_attack() {
    running = false;
    for (auto& t : attackers) t.join();
    attackers.clear();
  }

  std::string dir, base;
  int web = 0;
  std::unique_ptr<DaemonProcess> daemon;
  std::atomic<bool> running{true};
  std::atomic<int> checked{0}, held_back{0}, busy{0};
  std::vector<std::thread> attackers;
};

TEST_F(LoginAttackers, GuessingIsSlowFromAnyNumberOfAddressesAndTheOwnerGetsIn) {
  const std::string jar = dir + "/owner";
  // The owner set the password from this browser: it holds a device cookie.
  const std::string set = curl("-c " + jar + " " + login_json() + base + "/api/password");
  ASSERT_EQ(status_of(set), 200) << set;
  ASSERT_NE(set.find("rotord_device="), std::string::npos) << set;

  const auto wall_start = std::chrono::steady_clock::now();
  long long advanced_ms = 0;
  start_attack();
  // Phase 1: access control by password only; the owner's browser.
  // A round is 6 s of the network's clock, a second at a time; the owner
  // tries in the middle of it, whatever the attackers are doing then.
  const auto half_round = [&] {
    for (int s = 0; s < 3; ++s) daemon->advance_ms(1000);
    advanced_ms += 3000;
  };
  int with_cookie = 0;
  for (int round = 0; round < 20; ++round) {
    half_round();
    const std::string r =
        curl("-b " + jar + " -c " + jar + " " + login_json() + base + "/api/login");
    if (status_of(r) == 200) ++with_cookie;
    half_round();
  }
  // Phase 2: the owner's address on the allow-list, a browser never seen.
  ASSERT_EQ(
      status_of(curl("-b " + jar + " --json '{\"access.control_networks\": \"127.0.0.1/32\"}' " +
                     base + "/api/settings")),
      200);
  int from_listed = 0;
  for (int round = 0; round < 20; ++round) {
    half_round();
    if (status_of(curl(login_json() + base + "/api/login")) == 200) ++from_listed;
    half_round();
  }
  stop_attack();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const double minutes = (static_cast<double>(advanced_ms) / 1000.0 + wall_s) / 60.0;
  const double per_minute = checked / minutes;
  std::printf(
      "[ measured ] 16 addresses guessing, 2 in flight, %.1f min of the network's clock: "
      "%d guesses checked (%.1f a minute in total), %d held back (429), %d busy (503)\n",
      minutes, checked.load(), per_minute, held_back.load(), busy.load());
  std::printf(
      "[ measured ] during the attack the owner logged in %d of 20 with the device cookie, "
      "%d of 20 from the listed address\n",
      with_cookie, from_listed);
  EXPECT_EQ(with_cookie, 20);
  EXPECT_EQ(from_listed, 20);
  // 10 a minute, and the burst of 2 once.
  EXPECT_LE(checked, static_cast<int>(10 * minutes) + 2);
  EXPECT_GE(held_back, checked);  // the budget, not the attackers' pace, set the rate
  daemon->advance_ms(10);
  EXPECT_NE(daemon->output().find("failed web login from 127.0.1."), std::string::npos);
}

TEST_F(LoginAttackers, ADeviceCookieIsBoundToThePassword) {
  const std::string jar = dir + "/owner";
  ASSERT_EQ(status_of(curl("-c " + jar + " " + login_json() + base + "/api/password")), 200);
  const std::string forged = "-H 'Cookie: rotord_device=" + std::string(64, 'a') + "' ";
  // A forged cookie is a stranger: its guesses spend the strangers' budget.
  for (int n = 0; n < 3; ++n)
    curl(forged + "--json '{\"password\":\"wrong\"}' " + base + "/api/login");
  EXPECT_EQ(status_of(curl(forged + login_json() + base + "/api/login")), 429);
  // The real one is recognised, and logs in at once.
  EXPECT_EQ(status_of(curl("-b " + jar + " " + login_json() + base + "/api/login")), 200);
  // A new password: the old device cookie is a stranger's again.
  ASSERT_EQ(status_of(curl("-b " + jar + " --json '{\"password\":\"another horse\"}' " + base +
                           "/api/password")),
            200);
  const std::string old_cookie =
      curl("-b " + jar + " --json '{\"password\":\"x\"}' " + base + "/api/login");
  EXPECT_EQ(status_of(old_cookie), 429) << old_cookie;
}

}  // namespace
}  // namespace rotord::testing
