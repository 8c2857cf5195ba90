// The REST API and the settings file over real TCP against a running rotord
// on the simulated G-5500, with --config in a temporary dir. The daemon runs
// on a manual clock that the tests advance, except where the wall clock's
// pace is the thing under test (the event stream's push rate).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "file_text.hpp"
#include "http_client.hpp"
#include "poll.hpp"

namespace rotord::testing {
namespace {

namespace fs = std::filesystem;

using Response = HttpResponse;

double number(const std::string& json, const std::string& key, std::size_t from = 0) {
  return json_number(json, key, from);
}

double az_of(const std::string& status) {
  return number(status, "position_deg", status.find("\"az\":{"));
}

class WebApi : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("rotord-web-api-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    config = dir / "conf" / "settings.json";  // the daemon creates conf/ on the first save
  }
  void TearDown() override {
    daemon.reset();
    fs::remove_all(dir);
  }
  enum class Clock { kManual, kWallSpeedup10 };
  void start(const std::string& profile = "g5500", Clock clock = Clock::kManual) {
    std::vector<std::string> args{"--sim", profile, "--config", config.string()};
    const std::vector<std::string> timing = clock == Clock::kManual
                                                ? std::vector<std::string>{"--clock", "manual"}
                                                : std::vector<std::string>{"--speedup", "10"};
    args.insert(args.end(), timing.begin(), timing.end());
    daemon = std::make_unique<DaemonProcess>(args);
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    port = daemon->ports().web;
  }
  std::string status() { return http(port, "GET", "/api/status").body; }
  /// Runs `ms` of controller time in the daemon.
  void advance(long long ms) { ASSERT_GE(daemon->advance_ms(ms), 0) << daemon->output(); }
  /// Advances controller time until the azimuth stands still; returns the
  /// last status.
  std::string settled_status() {
    std::string s;
    for (int n = 0; n < 200; ++n) {
      s = status();
      if (s.find("\"moving\":false") != std::string::npos) break;
      advance(500);
    }
    return s;
  }

  fs::path dir;
  fs::path config;
  std::unique_ptr<DaemonProcess> daemon;
  int port = 0;
};

TEST_F(WebApi, GotoMovesTheSimulatedRotatorAndStatusFollows) {
  start();
  Response r = http(port, "POST", "/api/goto", R"({"az": 120})");
  ASSERT_EQ(r.status, 200) << r.body;
  double az = 0;
  for (int n = 0; n < 200; ++n) {
    const std::string s = status();
    az = az_of(s);
    if (std::abs(az - 120) <= 1.0 && s.find("\"moving\":false") != std::string::npos) break;
    advance(1000);
  }
  EXPECT_NEAR(az, 120, 1.0);
}

TEST_F(WebApi, HoldToMoveStopsWhenRenewalsStop) {
  start();
  const double before = az_of(status());
  // hold_ms is the client's (wall-clock) time and the dead-man runs on the
  // transport's clock: renewals in quick succession keep the jog alive while
  // controller time turns the rotator.
  for (int n = 0; n < 10; ++n) {
    ASSERT_EQ(http(port, "POST", "/api/move", R"({"dir":"ccw","hold_ms":5000})").status, 200);
    advance(300);
  }
  EXPECT_NE(status().find("\"jogging\":true"), std::string::npos);
  ASSERT_EQ(http(port, "POST", "/api/move", R"({"dir":"ccw","hold_ms":300})").status, 200);
  // The dead-man after the last renewal is the thing under test. It runs on
  // the network's clock, which the manual clock moves too: run it out without
  // waiting (a bounded walk, 10 s of controller time at most, never timed).
  std::string s = status();
  for (int n = 0; n < 100 && s.find("\"jogging\":true") != std::string::npos; ++n) {
    advance(100);
    s = status();
  }
  EXPECT_EQ(s.find("\"jogging\":true"), std::string::npos) << s;
  s = settled_status();
  EXPECT_EQ(s.find("\"jogging\":true"), std::string::npos) << s;
  EXPECT_NE(s.find("\"moving\":false"), std::string::npos) << s;
  EXPECT_LT(az_of(s), before - 2.0);  // it did move CCW meanwhile
}

TEST_F(WebApi, EveryCommandEndpointAndItsErrors) {
  start();
  EXPECT_EQ(http(port, "POST", "/api/stop", "", "").status, 200);
  EXPECT_EQ(http(port, "POST", "/api/park", "{}").status, 200);
  EXPECT_NE(status().find("\"mode\":\"park\""), std::string::npos);
  EXPECT_EQ(http(port, "POST", "/api/mode", R"({"mode":"idle"})").status, 200);
  EXPECT_EQ(http(port, "POST", "/api/speed", R"({"speed_pct":30})").status, 200);
  EXPECT_NE(status().find("\"speed_pct\":30"), std::string::npos);
  EXPECT_EQ(http(port, "POST", "/api/reset", "").status, 200);
  EXPECT_NE(status().find("\"speed_pct\":100"), std::string::npos);
  // The park was stopped; let the motor coast out (a loaded machine runs the
  // simulation slower), so "nothing moves" below means the bad requests.
  settled_status();
  ASSERT_NE(status().find("\"moving\":false"), std::string::npos) << status();

  Response r = http(port, "POST", "/api/goto", R"({"az": 9999})");
  EXPECT_EQ(r.status, 422);
  EXPECT_NE(r.body.find("\"error\":"), std::string::npos);
  EXPECT_EQ(http(port, "POST", "/api/goto", R"({"az": )").status, 400);
  EXPECT_EQ(http(port, "POST", "/api/goto", R"({"az": "x"})").status, 400);
  EXPECT_EQ(http(port, "POST", "/api/goto", R"({"az": 10})", "text/plain").status, 415);
  EXPECT_EQ(http(port, "POST", "/api/move", R"({"dir":"sideways"})").status, 422);
  EXPECT_EQ(http(port, "POST", "/api/mode", R"({"mode":"warp"})").status, 422);
  EXPECT_EQ(http(port, "GET", "/api/nothing").status, 404);
  EXPECT_EQ(http(port, "GET", "/api/goto").status, 405);
  EXPECT_EQ(http(port, "POST", "/api/settings", std::string(100000, ' ')).status, 413);
  const std::string after = status();
  EXPECT_NE(after.find("\"moving\":false"), std::string::npos) << after;
  const auto count = [&after](const std::string& what) {
    std::size_t n = 0;
    for (auto at = after.find(what); at != std::string::npos; at = after.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("\"target_deg\":null"), count("\"target_deg\":")) << "no go-to started";
}

TEST_F(WebApi, AssetsAndSchema) {
  start();
  Response r = http(port, "GET", "/");
  EXPECT_EQ(r.status, 200);
  EXPECT_NE(r.head.find("Content-Encoding: gzip"), std::string::npos);
  r = http(port, "GET", "/api/settings/schema");
  EXPECT_EQ(r.status, 200);
  EXPECT_NE(r.body.find("\"key\":\"az.pot_cal_lo_counts\""), std::string::npos);
}

TEST_F(WebApi, EventStreamSendsAtLeastFivePerSecondWhileMoving) {
  start("g5500", Clock::kWallSpeedup10);  // the push rate on the wall clock is under test
  ASSERT_EQ(http(port, "POST", "/api/goto", R"({"az": 400})").status, 200);
  TcpClient c(port);
  c.send("GET /api/events HTTP/1.1\r\nHost: localhost\r\nAccept: text/event-stream\r\n\r\n");
  std::string data;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (std::chrono::steady_clock::now() < end) data += c.recv_once(100);
  std::size_t events = 0;
  for (auto pos = data.find("data: {"); pos != std::string::npos;
       pos = data.find("data: {", pos + 1))
    ++events;
  EXPECT_GE(events, 5u) << data.substr(0, 300);
  EXPECT_NE(data.find("Content-Type: text/event-stream"), std::string::npos);
}

TEST_F(WebApi, TooManyConnectionsGetA503AndOthersKeepWorking) {
  start();
  // Eight hosts (one host alone gets at most net.max_per_address, 6), each
  // within its request deadline: the port is full.
  std::vector<std::unique_ptr<TcpClient>> held;
  for (int n = 1; n <= 8; ++n) {
    held.push_back(std::make_unique<TcpClient>(port, "127.0.0." + std::to_string(n)));
    held.back()->send("GET /api/sta");  // slow clients: half a request each
  }
  // The daemon takes the eight in on its own loop: ask until it answers that
  // the port is full (each answer comes at once and closes; a bounded poll
  // for the condition, no wait).
  int full_status = 0;
  for (int n = 0; n < 100 && full_status != 503; ++n)
    full_status = http(port, "GET", "/api/status").status;
  EXPECT_EQ(full_status, 503);
  // A newcomer to a full port may still say STOP for 2 s (issue 29), then
  // gets the 503: run those 2 s on the network's clock.
  TcpClient extra(port, "127.0.0.9");
  daemon->advance_ms(2100);
  extra.wait_closed(3000);
  EXPECT_EQ(extra.recv_once(0).rfind("HTTP/1.1 503", 0), 0u);
  held.clear();
  // The daemon sees the closes from its sockets, in its own time: ask again
  // until a slot is free (a bounded poll; each refusal answers at once).
  int status = 0;
  for (int n = 0; n < 100 && status != 200; ++n) status = http(port, "GET", "/api/status").status;
  EXPECT_EQ(status, 200);
}

TEST_F(WebApi, SettingsArePersistedAndSurviveARestart) {
  start();
  Response r = http(port, "POST", "/api/settings", R"({"park.az_deg": 123.5, "az.max_deg": 9999})");
  EXPECT_EQ(r.status, 422);
  EXPECT_NE(r.body.find("\"az.max_deg\":"), std::string::npos);
  EXPECT_FALSE(fs::exists(config));  // nothing saved on error
  r = http(port, "POST", "/api/settings", R"({"park.az_deg": 123.5})");
  ASSERT_EQ(r.status, 200) << r.body;
  ASSERT_TRUE(fs::exists(config));
  EXPECT_NE(read_file(config).find("\"park.az_deg\": 123.5"), std::string::npos);
  daemon.reset();
  start();
  EXPECT_NE(daemon->output().find("settings loaded from"), std::string::npos) << daemon->output();
  EXPECT_NE(http(port, "GET", "/api/settings").body.find("\"park.az_deg\":123.5"),
            std::string::npos);
  // Reset to defaults is persisted too: the file keeps no change of the user's.
  ASSERT_EQ(http(port, "POST", "/api/settings/reset", "{}").status, 200);
  EXPECT_EQ(read_file(config), "{\n  \"settings_version\": 2\n}\n");
}

TEST_F(WebApi, TextSettingsSecretsAreNeverReadBackAndTheMaskKeepsThem) {
  start();
  Response r = http(port, "POST", "/api/settings",
                    R"({"wifi.ssid": "Shack Net", "wifi.password": "hunter2-wpa2-pass"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.body.find("\"restart_required\":[\"wifi.ssid\",\"wifi.password\"]"),
            std::string::npos)
      << r.body;
  // The stored file has the password (the device needs it); no reader sees it.
  EXPECT_NE(read_file(config).find("\"wifi.password\": \"hunter2-wpa2-pass\""), std::string::npos);
  std::string doc = http(port, "GET", "/api/settings").body;
  EXPECT_EQ(doc.find("hunter2"), std::string::npos) << doc;
  EXPECT_NE(doc.find("\"wifi.password\":\"********\""), std::string::npos) << doc;
  EXPECT_NE(doc.find("\"wifi.ssid\":\"Shack Net\""), std::string::npos) << doc;
  EXPECT_NE(doc.find("\"wifi.ap_password\":\"\""), std::string::npos) << "nothing stored";
  EXPECT_EQ(http(port, "GET", "/api/settings/schema").body.find("hunter2"), std::string::npos);
  {
    TcpClient rotctl(daemon->ports().rotctld);
    ASSERT_TRUE(rotctl.connected());
    EXPECT_EQ(rotctl.ask("\\get_conf wifi.password\n"), "wifi.password=********");
    // Never written through a line protocol (issue 12): RIG_ERJCTED.
    EXPECT_EQ(rotctl.ask("C wifi.password attacker-pass\n"), "RPRT -9");
  }

  // The whole document as read (an export imported again) keeps the password.
  r = http(port, "POST", "/api/settings", doc);
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.body.find("wifi."), std::string::npos) << "nothing Wi-Fi changed: " << r.body;
  EXPECT_NE(read_file(config).find("\"wifi.password\": \"hunter2-wpa2-pass\""), std::string::npos);

  // A bad address is refused with the reason, and nothing is saved.
  r = http(port, "POST", "/api/settings",
           R"({"net.ipv4_mode": "static", "net.ipv4_address": "192.168.1.256"})");
  EXPECT_EQ(r.status, 422);
  EXPECT_NE(r.body.find("\"net.ipv4_address\":\"not an IPv4 address"), std::string::npos) << r.body;
  r = http(port, "POST", "/api/settings", R"({"net.ipv4_mode": "static"})");
  EXPECT_EQ(r.status, 422);
  EXPECT_NE(r.body.find("needs net.ipv4_address"), std::string::npos) << r.body;
  r = http(port, "POST", "/api/settings", R"({"wifi.password": "short"})");
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(read_file(config).find("net.ipv4_mode"), std::string::npos);  // still the default
  EXPECT_NE(read_file(config).find("hunter2-wpa2-pass"), std::string::npos);

  // After a restart the stored password is still there and still hidden.
  daemon.reset();
  start();
  doc = http(port, "GET", "/api/settings").body;
  EXPECT_NE(doc.find("\"wifi.password\":\"********\""), std::string::npos) << doc;
  // Clearing it (an open network) is a change like any other.
  r = http(port, "POST", "/api/settings", R"({"wifi.password": ""})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(read_file(config).find("hunter2"), std::string::npos);
  EXPECT_NE(http(port, "GET", "/api/settings").body.find("\"wifi.password\":\"\""),
            std::string::npos);
}

TEST_F(WebApi, StatusHasTheUtcTimeFromTheSystemClock) {
  start();
  const std::string s = status();
  const auto pos = s.find("\"time_utc\":\"");
  ASSERT_NE(pos, std::string::npos) << s;
  const std::string utc = s.substr(pos + 12, 24);  // 2026-11-23T17:40:11.250Z
  EXPECT_EQ(utc.size(), 24u);
  EXPECT_EQ(utc[4], '-');
  EXPECT_EQ(utc[10], 'T');
  EXPECT_EQ(utc[23], 'Z');
  EXPECT_GE(std::atoi(utc.c_str()), 2024) << utc;
}

TEST_F(WebApi, ADamagedFileIsReportedKeptAndItsValidValuesRun) {
  fs::create_directories(config.parent_path());
  const std::string damaged = "{\"park.az_deg\": 45, \"az.max_deg\": 99999}";  // edited by hand
  std::ofstream(config) << damaged;
  start();
  EXPECT_NE(daemon->output().find("az.max_deg: outside the allowed range: dropped"),
            std::string::npos)
      << daemon->output();
  EXPECT_EQ(read_file(config), damaged);  // not overwritten
  const std::string values = http(port, "GET", "/api/settings").body;
  EXPECT_NE(values.find("\"park.az_deg\":45,"), std::string::npos) << values;  // kept
  EXPECT_NE(values.find("\"az.max_deg\":450,"), std::string::npos) << values;  // dropped
  // The settings page shows what was dropped.
  EXPECT_NE(
      status().find(R"("settings_load":{"access_unreadable":false,"dropped":[{"key":"az.max_deg")"),
      std::string::npos);
  // An explicit save replaces it and keeps the damaged one aside.
  ASSERT_EQ(http(port, "POST", "/api/settings", R"({"park.az_deg": 10})").status, 200);
  EXPECT_EQ(read_file(config.string() + ".bad"), damaged);
  EXPECT_NE(read_file(config).find("\"park.az_deg\": 10"), std::string::npos);
}

TEST_F(WebApi, AKillDuringSavingNeverLeavesABrokenFile) {
  for (int round = 0; round < 4; ++round) {
    start();
    std::atomic<bool> run{true};
    std::atomic<int> answered{0};
    std::thread writer([&] {
      for (int n = 0; run; ++n) {
        http(port, "POST", "/api/settings",
             "{\"park.az_deg\": " + std::to_string(n % 300) +
                 ", \"az.offset_deg\": " + std::to_string((n % 7) - 3) + "}");
        answered.fetch_add(1);
        answered.notify_all();
      }
    });
    // A kill at a different moment of the writes each round: after another
    // number of answered saves, while the writer sends the next one (waits
    // on the writer's count, not on the clock).
    const int kill_after = 3 + 5 * round;
    for (int seen = answered.load(); seen < kill_after; seen = answered.load()) answered.wait(seen);
    ::kill(daemon->pid(), SIGKILL);
    run = false;
    writer.join();
    daemon.reset();
    if (fs::exists(config)) {
      const std::string doc = read_file(config);
      EXPECT_EQ(doc.front(), '{') << doc;
      EXPECT_EQ(doc.substr(doc.size() - 2), "}\n") << doc;
    }
    start();
    EXPECT_EQ(daemon->output().find("is invalid"), std::string::npos) << daemon->output();
    daemon.reset();
  }
}

TEST_F(WebApi, RebootRestartsTheControllerWithRestartOnlySettings) {
  start();
  Response r = http(port, "POST", "/api/settings", R"({"el.enabled": false})");
  ASSERT_EQ(r.status, 200);
  EXPECT_NE(r.body.find("\"restart_required\":[\"el.enabled\"]"), std::string::npos) << r.body;
  EXPECT_NE(status().find("\"has_el\":true"), std::string::npos);
  r = http(port, "POST", "/api/reboot", "{}");
  EXPECT_EQ(r.status, 202);
  // The reboot is scheduled on the wall clock (200 ms after the reply has
  // gone out, whatever the manual clock does): poll until it happened; the
  // 20 s bound is for a loaded 2-core machine (5 s failed 1 run in 5 there).
  std::string s;
  poll_until(
      [&] {
        s = status();
        return s.find("\"has_el\":false") != std::string::npos;
      },
      std::chrono::seconds(20));
  EXPECT_NE(s.find("\"has_el\":false"), std::string::npos) << s;
  EXPECT_NE(s.find("\"el\":null"), std::string::npos);
}

TEST_F(WebApi, StatusCarriesThePotReadingInVoltsForTheCalibrationPage) {
  start();
  const std::string s = status();
  for (const char* axis : {"\"az\":{", "\"el\":{"}) {
    const std::size_t at = s.find(axis);
    ASSERT_NE(at, std::string::npos) << s;
    EXPECT_EQ(s.find("\"sensor\":\"pot\"", at), s.find("\"sensor\"", at)) << s;
    const double raw = number(s, "raw", at);
    EXPECT_GT(raw, 0);
    // The simulator's ADC is the Pico's: 12 bits at 3.3 V.
    EXPECT_EQ(number(s, "raw_full_scale", at), 4095);
    EXPECT_NEAR(number(s, "raw_volts", at), raw * 3.3 / 4095, 1e-4);
    EXPECT_EQ(s.find("\"mag\":null", at), s.find("\"mag\":", at)) << s;
  }
}

TEST_F(WebApi, ACalibrationWithAnOffsetReadsTheEnteredAngleAndLatchesNoFault) {
  start();
  ASSERT_EQ(http(port, "POST", "/api/settings", R"({"az.offset_deg": 10})").status, 200);
  const std::string before = settled_status();
  const double raw = number(before, "raw", before.find("\"az\":{"));
  // "The antenna points at 200 now": the calibration angle excludes the offset.
  const std::string body =
      "{\"az.pot_cal_lo_counts\": " + std::to_string(raw) + ", \"az.pot_cal_lo_deg\": 190}";
  ASSERT_EQ(http(port, "POST", "/api/settings", body).status, 200);
  advance(300);
  const std::string s = settled_status();
  EXPECT_NEAR(az_of(s), 200, 0.5) << s;
  EXPECT_NE(s.find("\"fault\":false"), std::string::npos) << s;
}

TEST_F(WebApi, Ma3StatusGivesTheCodeRangeAndANewZeroTakesEffectWithoutAFault) {
  start("spid");
  const std::string s0 = settled_status();
  const std::size_t az = s0.find("\"az\":{");
  EXPECT_NE(s0.find("\"sensor\":\"ma3\"", az), std::string::npos) << s0;
  EXPECT_NE(s0.find("\"raw_unit\":\"code\"", az), std::string::npos) << s0;
  EXPECT_EQ(number(s0, "raw_full_scale", az), 4096);
  EXPECT_EQ(s0.find("\"raw_volts\":null", az), s0.find("\"raw_volts\":", az)) << s0;
  // Zero the encoder so that this position reads 7 deg more: what the web
  // page's "set this position as N" computes.
  const double code_deg = number(s0, "raw", az) * 360.0 / 4096.0;
  const double want = az_of(s0) + 7;
  double zero = std::fmod(code_deg - want + 720.0, 360.0);
  const std::string body = "{\"az.ma3_zero_deg\": " + std::to_string(zero) + "}";
  ASSERT_EQ(http(port, "POST", "/api/settings", body).status, 200);
  advance(300);
  const std::string s = settled_status();
  EXPECT_NEAR(az_of(s), want, 0.3) << s;
  EXPECT_NE(s.find("\"fault\":false"), std::string::npos) << s;
}

}  // namespace
}  // namespace rotord::testing
