// The tracking and care commands in the command layer (core/command/
// care_commands.hpp, issue 25): starting and ending a track, resetting the
// wear odometer, overriding the wind stow and ending the override each
// exist once, and write the same log line whichever front end took them
// (REST, the console), done or refused; and MQTT's two refusals, decided in
// the command layer now, answer the same bytes as before with one DENIED
// line each.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "command/care_commands.hpp"
#include "command/command_log.hpp"
#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "mqtt/bridge.hpp"
#include "mqtt_last_result.hpp"
#include "protocol/console_session.hpp"
#include "web/http_session.hpp"

namespace rotord::command {
namespace {

using rotord::testing::StringSink;
using SettingId = settings::Id;

/// The port's side of the log: each write() is one line.
using Lines = rotord::testing::LineSink;

/// UTC known and synchronized: tracking may start.
class Utc final : public hal::WallClock {
 public:
  std::optional<std::int64_t> unix_ms() const override {
    return 1767225600000;  // 2026-01-01
  }
};

const access::Peer kClient = access::Peer::from_ipv4(0xC0A8011Eu);  // 192.168.1.30

/// One rotator with its log, driven through REST or the console.
struct Front {
  explicit Front(bool console) : console_front(console) {
    r.settings.set(SettingId::kWindSource, 1);  // MQTT: fed by wind_speed_message
    r.run_ms(50);
    r.controller->attach_journal(&log);
    r.controller->attach_utc_clock(&utc);
    rest.set_peer(kClient);
    console_session.set_peer(kClient);
  }
  /// The same request in each front end's bytes.
  std::string send(const std::string& rest_method, const std::string& path, const std::string& body,
                   const std::string& console_line) {
    StringSink sink;
    if (console_front) {
      console_session.receive(console_line + "\r\n", sink);
    } else if (rest_method == "DELETE") {
      rest.receive("DELETE " + path + " HTTP/1.1\r\nHost: localhost\r\n\r\n", sink);
    } else {
      rest.receive(rotord::testing::post_request(path, body), sink);
    }
    return sink.data;
  }
  /// The wind holds 25 m/s past wind.hold_s: stowed for the wind.
  void storm() {
    for (int s = 0; s < 15; ++s) {
      r.controller->wind_speed_message("25");
      r.run_ms(1000);
    }
  }
  /// The last line, with the front end's name taken out.
  std::string last() const {
    if (log_lines.lines.empty()) return "(none)";
    std::string line = log_lines.lines.back();
    const std::string front = console_front ? "from console" : "from rest";
    if (const std::size_t at = line.find(front); at != std::string::npos)
      line.replace(at, front.size(), "from <front>");
    return line;
  }

  bool console_front;
  rotord::testing::FakeRotator r;
  Utc utc;
  Lines log_lines;
  CommandLog log{log_lines};
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "1"}};
  web::HttpSession rest{api};
  protocol::ConsoleSession console_session{*r.controller, "1", nullptr};
};

TEST(CareCommands, RestAndTheConsoleWriteTheSameLineForTheOdometerAndTheWind) {
  Front rest(false), console(true);
  std::vector<std::string> lines[2];
  int n = 0;
  for (Front* f : {&rest, &console}) {
    Millis now = 0;
    auto step = [&](const char* method, const char* path, const char* body, const char* line) {
      now += CommandLog::kWindowMs;  // a minute apart: no line is a repeat
      f->log.poll(now);
      const std::size_t before = f->log_lines.lines.size();
      f->send(method, path, body, line);
      // One line each, done or refused.
      EXPECT_EQ(f->log_lines.lines.size(), before + 1) << line;
      lines[n].push_back(f->last());
    };
    step("POST", "/api/odometer/reset", "{}", "odometer reset");
    step("POST", "/api/wind/override", R"({"minutes": 30})", "wind override 30");
    step("POST", "/api/wind/override", R"({"end": true})", "wind stow");
    f->storm();
    ASSERT_EQ(f->r.controller->wind().state(), care::WindState::kStowed);
    step("POST", "/api/wind/override", R"({"minutes": 30})", "wind override 30");
    EXPECT_EQ(f->r.controller->wind().state(), care::WindState::kOverride);
    step("POST", "/api/wind/override", R"({"end": true})", "wind stow");
    EXPECT_EQ(f->r.controller->wind().state(), care::WindState::kStowed);
    step("POST", "/api/wind/override", "{}", "wind override");
    ++n;
  }
  const std::vector<std::string> want = {
      "command odometer reset from <front> (192.168.1.30): OK",
      "command wind override 30 from <front> (192.168.1.30): NOT FOUND",
      "command wind stow from <front> (192.168.1.30): NOT FOUND",
      "command wind override 30 from <front> (192.168.1.30): OK",
      "command wind stow from <front> (192.168.1.30): OK",
      "command wind override from <front> (192.168.1.30): OK",
  };
  EXPECT_EQ(lines[0], want);
  EXPECT_EQ(lines[1], want);
}

// Another operator holds the control lock: REST answers 423, the console
// its error, and both write the same LOCKED line; nothing is reset.
TEST(CareCommands, ALockedRefusalWritesTheSameLineFromRestAndTheConsole) {
  for (const bool console : {false, true}) {
    Front f(console);
    f.r.controller->control_lock().take({}, 3600000);
    const std::string reply = f.send("POST", "/api/odometer/reset", "{}", "odometer reset");
    EXPECT_NE(reply.find(console ? "error: read-only" : "HTTP/1.1 423"), std::string::npos)
        << reply;
    EXPECT_EQ(f.last(), "command odometer reset from <front> (192.168.1.30): LOCKED");
    f.send("POST", "/api/wind/override", R"({"minutes": 5})", "wind override 5");
    EXPECT_EQ(f.last(), "command wind from <front> (192.168.1.30): LOCKED");
  }
}

// REST's tracking mode: a track started and ended, each with its line; a
// refused one (an elevation above the travel) with the refusal's status.
TEST(CareCommands, ATrackStartedAndEndedThroughRestWritesItsLines) {
  Front f(false);
  std::string reply = f.send("POST", "/api/track", R"({"az": 120, "el": 30, "when": "now"})", "");
  EXPECT_NE(reply.find("HTTP/1.1 200"), std::string::npos) << reply;
  EXPECT_EQ(f.log_lines.lines.back(),
            "command track start az 120.0 el 30.0 from rest (192.168.1.30): OK");
  reply = f.send("DELETE", "/api/track", "", "");
  EXPECT_NE(reply.find("HTTP/1.1 200"), std::string::npos) << reply;
  EXPECT_EQ(f.log_lines.lines.back(), "command track stop from rest (192.168.1.30): OK");
  reply = f.send("POST", "/api/track", R"({"body": "sun", "when": "now"})", "");
  EXPECT_NE(reply.find("HTTP/1.1 409"), std::string::npos) << reply;  // no station set
  EXPECT_EQ(f.log_lines.lines.back(), "command track start sun from rest (192.168.1.30): CONFLICT");
  // The typed command, as any other front end would call it.
  TrackRequest moon;
  moon.kind = tracking::TargetKind::kMoon;
  EXPECT_EQ(track(*f.r.controller, {"console", access::Peer::line()}, moon),
            TrackError::kNoStation);
  EXPECT_EQ(f.log_lines.lines.back(),
            "command track start moon from console (a serial port): CONFLICT");
  // A satellite by its name, or its catalog number without a title line.
  TrackRequest iss;
  iss.kind = tracking::TargetKind::kSatellite;
  iss.tle.catalog = 25544;
  EXPECT_EQ(track(*f.r.controller, {"rest", kClient}, iss), TrackError::kNoStation);
  EXPECT_EQ(f.log_lines.lines.back(),
            "command track start 25544 from rest (192.168.1.30): CONFLICT");
  std::snprintf(iss.tle.name, sizeof iss.tle.name, "ISS (ZARYA)");
  f.log.poll(CommandLog::kWindowMs);
  EXPECT_EQ(track(*f.r.controller, {"rest", kClient}, iss), TrackError::kNoStation);
  EXPECT_EQ(f.log_lines.lines.back(),
            "command track start ISS (ZARYA) from rest (192.168.1.30): CONFLICT");
}

using rotord::testing::LastResult;

// MQTT's two refusals, now the command layer's (Commands::from_broker):
// the same status and body as the bridge answered before, one DENIED line
// each; STOP is still obeyed.
TEST(CareCommands, MqttsRefusalsAnswerTheSameBytesWithOneDeniedLine) {
  rotord::testing::FakeRotator r;
  r.run_ms(50);
  Lines lines;
  CommandLog log{lines};
  r.controller->attach_journal(&log);
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "1"}};
  LastResult broker;
  mqtt::Bridge bridge{api, broker, "rotord/t", "rotord_t", "t"};
  bridge.set_broker_peer(access::Peer::from_ipv4(0xC0A80102u));  // 192.168.1.2

  r.settings.set(SettingId::kMqttControl, 0);
  bridge.on_message("rotord/t/cmd/goto", R"({"az": 100})");
  EXPECT_EQ(broker.result,
            R"({"cmd":"goto","status":403,"response":{"error":"mqtt.control is off: only stop )"
            R"(is obeyed from the broker"}})");
  ASSERT_EQ(lines.lines.size(), 1u);
  EXPECT_EQ(lines.lines[0], "command goto from mqtt (192.168.1.2): DENIED");

  r.settings.set(SettingId::kMqttControl, 1);
  ASSERT_EQ(r.settings.set_text(SettingId::kAccessControlNetworks, "10.0.0.0/8").error, Error::kOk);
  log.poll(CommandLog::kWindowMs);
  bridge.on_message("rotord/t/cmd/park", "{}");
  EXPECT_EQ(broker.result,
            R"({"cmd":"park","status":403,"response":{"error":"read-only: the broker's address )"
            R"(is not in access.control_networks"}})");
  ASSERT_EQ(lines.lines.size(), 2u);
  EXPECT_EQ(lines.lines[1], "command park from mqtt (192.168.1.2): DENIED");

  bridge.on_message("rotord/t/cmd/stop", "");
  EXPECT_EQ(broker.result, R"({"cmd":"stop","status":200,"response":{"ok":true}})");
  EXPECT_EQ(lines.lines.back(), "command stop from mqtt (192.168.1.2): OK");
}

}  // namespace
}  // namespace rotord::command
