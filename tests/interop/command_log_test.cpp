// The command log through the real daemon (issue 25, docs/logging.md): a
// real Hamlib `rotctl -m 2` go-to and a REST go-to with curl each write
// their one line into the daemon's log (standard output: the journal under
// systemd), a refused `P` its refusal, and rotctl's position queries write
// none; the tracking mode's start and end, the odometer's reset and a wind
// override through REST write theirs; a settings write its line with the
// key, never the value; a REST preset its row's settings write; a REST
// reboot its line before the restart.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class CommandLog : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon = std::make_unique<DaemonProcess>(
        std::vector<std::string>{"--sim", "g5500", "--clock", "manual"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
  }
  CommandOutput rotctl(const std::string& commands) {
    return run_command("timeout 20 rotctl -m 2 -r 127.0.0.1:" +
                       std::to_string(daemon->ports().rotctld) + " " + commands + " 2>&1");
  }
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(CommandLog, RotctlAndRestGoTosEachWriteTheirLineAndQueriesNone) {
  const CommandOutput go = rotctl("P 120 30");
  ASSERT_EQ(go.rc, 0) << go.out;
  EXPECT_TRUE(
      daemon->wait_for_output("rotord: command goto az 120.0 el 30.0 from rotctld (127.0.0.1): OK"))
      << daemon->output();

  const HttpResponse rest = http(daemon->ports().web, "POST", "/api/goto", R"({"az": 200})");
  ASSERT_EQ(rest.status, 200) << rest.body;
  EXPECT_TRUE(daemon->wait_for_output("rotord: command goto az 200.0 from rest (127.0.0.1): OK"))
      << daemon->output();
  const HttpResponse far = http(daemon->ports().web, "POST", "/api/goto", R"({"az": 999})");
  EXPECT_EQ(far.status, 422) << far.body;
  EXPECT_TRUE(daemon->wait_for_output("rotord: command goto from rest (127.0.0.1): UNPROCESSABLE"))
      << daemon->output();

  // Ten position queries (each rotctl run also asks what it talks to):
  // not one line.
  daemon->advance_ms(100);
  const std::size_t lines = count_of(daemon->output(), "rotord: command ");
  const CommandOutput queries = rotctl("p p p p p p p p p p");
  ASSERT_EQ(queries.rc, 0) << queries.out;
  EXPECT_EQ(http(daemon->ports().web, "GET", "/api/status").status, 200);
  daemon->advance_ms(100);
  EXPECT_EQ(count_of(daemon->output(), "rotord: command "), lines) << daemon->output();
}

TEST_F(CommandLog, ARefusedRotctlGoToIsLoggedWithItsRefusal) {
  const HttpResponse set = http(daemon->ports().web, "POST", "/api/settings",
                                R"({"access.control_networks": "10.0.0.0/8"})");
  ASSERT_EQ(set.status, 200) << set.body;
  const CommandOutput go = rotctl("P 100 10");
  EXPECT_NE(go.rc, 0) << go.out;
  EXPECT_TRUE(daemon->wait_for_output("rotord: command set_pos from rotctld (127.0.0.1): DENIED"))
      << daemon->output();
  // STOP is for everyone, and logged as any command.
  EXPECT_EQ(rotctl("S").rc, 0);
  EXPECT_TRUE(daemon->wait_for_output("rotord: command stop from rotctld (127.0.0.1): OK"))
      << daemon->output();
}

// The tracking and care commands (core/command/care_commands.hpp) through
// the real daemon's REST API, with the clock known (--utc-start): a track of
// a fixed direction started and ended, the odometer reset, a wind override
// refused (nothing is stowed), each with its one line.
// POST /api/reboot is the command layer's reboot (system_commands.hpp): its
// line is written when it is asked for, then the daemon restarts.
TEST_F(CommandLog, ARestRebootWritesItsLineThenRestarts) {
  const HttpResponse r = http(daemon->ports().web, "POST", "/api/reboot", "{}");
  ASSERT_EQ(r.status, 202) << r.body;
  EXPECT_TRUE(daemon->wait_for_output("rotord: command reboot from rest (127.0.0.1): OK"))
      << daemon->output();
  EXPECT_TRUE(daemon->wait_for_output("restarting the controller")) << daemon->output();
}

TEST(CommandLogCare, RestTrackOdometerAndWindEachWriteTheirLine) {
  DaemonProcess daemon(std::vector<std::string>{"--sim", "g5500", "--clock", "manual",
                                                "--utc-start", "2019-12-09T19:15:00Z"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const int port = daemon.ports().web;
  HttpResponse r = http(port, "POST", "/api/track", R"({"az": 120, "el": 30})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(daemon.wait_for_output(
      "rotord: command track start az 120.0 el 30.0 from rest (127.0.0.1): OK"))
      << daemon.output();
  r = http(port, "DELETE", "/api/track");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(daemon.wait_for_output("rotord: command track stop from rest (127.0.0.1): OK"))
      << daemon.output();
  r = http(port, "POST", "/api/odometer/reset", "{}");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_TRUE(daemon.wait_for_output("rotord: command odometer reset from rest (127.0.0.1): OK"))
      << daemon.output();
  r = http(port, "POST", "/api/wind/override", R"({"minutes": 30})");
  EXPECT_EQ(r.status, 409) << r.body;
  EXPECT_TRUE(
      daemon.wait_for_output("rotord: command wind override 30 from rest (127.0.0.1): NOT FOUND"))
      << daemon.output();
  daemon.advance_ms(100);
  EXPECT_EQ(count_of(daemon.output(), "rotord: command track "), 2u) << daemon.output();
}

// A settings write is a command of the command layer too: POST
// /api/settings through the real daemon writes its line, naming the key and
// never the value, a password's least of all.
TEST_F(CommandLog, ASettingsWriteIsLoggedByItsKeyNeverItsValue) {
  const HttpResponse park =
      http(daemon->ports().web, "POST", "/api/settings", R"({"park.az_deg": 90})");
  ASSERT_EQ(park.status, 200) << park.body;
  EXPECT_TRUE(daemon->wait_for_output("rotord: command set park.az_deg from rest (127.0.0.1): OK"))
      << daemon->output();
  const HttpResponse bad =
      http(daemon->ports().web, "POST", "/api/settings", R"({"park.az_deg": 9999})");
  EXPECT_EQ(bad.status, 422) << bad.body;
  EXPECT_TRUE(daemon->wait_for_output(
      "rotord: command set park.az_deg from rest (127.0.0.1): INVALID ARGUMENT"))
      << daemon->output();
  const HttpResponse secret = http(daemon->ports().web, "POST", "/api/settings",
                                   R"({"wifi.password": "Interop5ecretValue"})");
  ASSERT_EQ(secret.status, 200) << secret.body;
  EXPECT_TRUE(
      daemon->wait_for_output("rotord: command set wifi.password from rest (127.0.0.1): OK"))
      << daemon->output();
  EXPECT_EQ(daemon->output().find("Interop5ecretValue"), std::string::npos) << daemon->output();
}

// A preset saved over REST is the settings write of its row (preset.N):
// through the real daemon it writes the console's `set` line, and the row
// is in the settings.
TEST_F(CommandLog, ARestPresetIsLoggedAsTheSettingsWriteOfItsRow) {
  const HttpResponse saved =
      http(daemon->ports().web, "POST", "/api/presets", R"({"name": "EU", "az": 45})");
  ASSERT_EQ(saved.status, 200) << saved.body;
  EXPECT_NE(saved.body.find(R"({"slot":1,"name":"EU","az_deg":45,"long_path":false})"),
            std::string::npos)
      << saved.body;
  EXPECT_TRUE(daemon->wait_for_output("rotord: command set preset.1 from rest (127.0.0.1): OK"))
      << daemon->output();
  const HttpResponse settings = http(daemon->ports().web, "GET", "/api/settings");
  EXPECT_NE(settings.body.find(R"("preset.1":"45.0:EU")"), std::string::npos) << settings.body;
}

}  // namespace
}  // namespace rotord::testing
