// The command layer's log line (core/command/command_log.hpp, issue 25):
// every command that changes something writes one line, once, in the
// command layer, whichever front end took it (a line protocol, REST, MQTT,
// the buttons), naming the command, its key arguments, the front end and
// client, and the outcome; refusals too (not in control, the control lock,
// out of range); queries write nothing; a client streaming commands cannot
// flood it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "command/command_log.hpp"
#include "command/typed.hpp"
#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "mqtt/bridge.hpp"
#include "protocol/rotctld_session.hpp"
#include "web/http_session.hpp"

namespace rotord::command {
namespace {

using rotord::testing::StringSink;
using SettingId = settings::Id;

/// The port's side of the log: each write() is one line.
using Lines = rotord::testing::LineSink;

access::Peer client(std::uint32_t last_octet) {
  return access::Peer::from_ipv4(0xC0A80100u | last_octet);  // 192.168.1.x
}

struct CommandLogTest : ::testing::Test {
  CommandLogTest() {
    r.run_ms(50);
    r.controller->attach_journal(&log);
  }
  rotord::testing::FakeRotator r;
  Lines out;
  CommandLog log{out};
};

TEST_F(CommandLogTest, EachChangingTypedCommandWritesOneLineWithItsSourceAndOutcome) {
  const Origin rotctld{"rotctld", client(20)};
  EXPECT_EQ(go_to(*r.controller, rotctld, 120.0f, 30.0f), Error::kOk);
  EXPECT_EQ(go_to(*r.controller, {"gs232", client(21)}, 500.0f, std::nullopt), Error::kOutOfRange);
  EXPECT_EQ(move(*r.controller, {"wrc", client(22)}, AxisId::kEl, Direction::kCcw), Error::kOk);
  stop(*r.controller, {"easycomm", access::Peer::line()});
  EXPECT_EQ(set_speed(*r.controller, {"seed", client(23)}, 50), Error::kOk);
  EXPECT_EQ(park(*r.controller, {"pst", client(24)}), Error::kOk);
  EXPECT_EQ(reset(*r.controller, {"console", access::Peer::line()}), Error::kOk);
  EXPECT_EQ(stop_axis(*r.controller, {"n1mm", client(25)}, AxisId::kAz), Error::kOk);
  settings::Preset p;
  EXPECT_EQ(turn_to_preset(*r.controller, {"console", access::Peer::line()}, "nowhere", p),
            Error::kNotFound);
  const std::vector<std::string> want = {
      "command goto az 120.0 el 30.0 from rotctld (192.168.1.20): OK",
      "command goto az 500.0 from gs232 (192.168.1.21): OUT OF RANGE",
      "command move el down from wrc (192.168.1.22): OK",
      "command stop from easycomm (a serial port): OK",
      "command speed 50 % from seed (192.168.1.23): OK",
      "command park from pst (192.168.1.24): OK",
      "command reset from console (a serial port): OK",
      "command stop az from n1mm (192.168.1.25): OK",
      "command preset nowhere from console (a serial port): NOT FOUND",
  };
  EXPECT_EQ(out.lines, want);
}

// Through a real session: rotctl's `P` writes its line, `p` (polled five
// times a second by Gpredict) writes none, and a refused client's `P` is
// logged with the refusal, by the command layer, not by the session.
TEST_F(CommandLogTest, ALineProtocolsCommandIsLoggedAndItsQueriesAreNot) {
  protocol::RotctldSession session(*r.controller, "1");
  session.set_peer(client(20));
  StringSink replies;
  for (int n = 0; n < 50; ++n) session.receive("p\n", replies);
  EXPECT_TRUE(out.lines.empty());
  session.receive("P 120 30\n", replies);
  session.receive("p\n", replies);
  ASSERT_EQ(out.lines.size(), 1u);
  EXPECT_EQ(out.lines[0], "command goto az 120.0 el 30.0 from rotctld (192.168.1.20): OK");

  // Not on access.control_networks: refused, and said so.
  ASSERT_EQ(r.settings.set_text(SettingId::kAccessControlNetworks, "10.0.0.0/8").error, Error::kOk);
  session.receive("P 130 30\n", replies);
  ASSERT_EQ(out.lines.size(), 2u);
  EXPECT_EQ(out.lines[1], "command set_pos from rotctld (192.168.1.20): DENIED");

  // The control lock, taken through the web, holds it back: LOCKED.
  ASSERT_EQ(r.settings.set_text(SettingId::kAccessControlNetworks, "").error, Error::kOk);
  r.controller->control_lock().take(access::LockHolder{}, r.now + 60'000);
  session.receive("P 140 30\n", replies);
  ASSERT_EQ(out.lines.size(), 3u);
  EXPECT_EQ(out.lines[2], "command set_pos from rotctld (192.168.1.20): LOCKED");
  // STOP is for everyone, and logged as any other.
  session.receive("S\n", replies);
  ASSERT_EQ(out.lines.size(), 4u);
  EXPECT_EQ(out.lines[3], "command stop from rotctld (192.168.1.20): OK");
}

// REST goes through Commands: one line per command (the typed command it
// calls writes none of its own), its refusal by the range check too, and
// none for a query.
TEST_F(CommandLogTest, ARestCommandWritesOneLineAndAQueryNone) {
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "1"}};
  web::HttpSession session{api};
  session.set_peer(client(30));
  StringSink sink;
  session.receive(
      rotord::testing::post_request("/api/goto", R"({"az": 200, "el": 10})", "application/json"),
      sink);
  session.receive(rotord::testing::post_request("/api/goto", R"({"az": 999})", "application/json"),
                  sink);
  session.receive("GET /api/status HTTP/1.1\r\nHost: x\r\n\r\n", sink);
  const std::vector<std::string> want = {
      "command goto az 200.0 el 10.0 from rest (192.168.1.30): OK",
      "command goto from rest (192.168.1.30): UNPROCESSABLE",
  };
  EXPECT_EQ(out.lines, want);
}

/// The MQTT boundary, which takes every message.
class AnyBroker final : public mqtt::Transport {
 public:
  bool connected() const override { return true; }
  bool publish(std::string_view, std::string_view, bool) override { return true; }
};

// REST and MQTT go through the same commands (Commands::execute): each
// command, done or refused, writes the same line from either, once.
TEST(CommandLogFrontEnds, RestAndMqttWriteTheSameLineForEachCommand) {
  rotord::testing::FakeRotator rest_rotator, mqtt_rotator;
  Lines rest_lines, mqtt_lines;
  CommandLog rest_log{rest_lines}, mqtt_log{mqtt_lines};
  for (rotord::testing::FakeRotator* r : {&rest_rotator, &mqtt_rotator}) {
    r->settings.set(SettingId::kMqttControl, 1);
    r->settings.set_text(SettingId::kPreset1, "150:EU");
    r->run_ms(50);
  }
  rest_rotator.controller->attach_journal(&rest_log);
  mqtt_rotator.controller->attach_journal(&mqtt_log);
  web::Api rest_api{web::ApiContext{*rest_rotator.controller, nullptr, nullptr, nullptr, "1"}};
  web::Api mqtt_api{web::ApiContext{*mqtt_rotator.controller, nullptr, nullptr, nullptr, "1"}};
  web::HttpSession session{rest_api};
  session.set_peer({access::Peer::Kind::kOther, 0, {}});  // the broker's kind, here
  AnyBroker broker;
  mqtt::Bridge bridge{mqtt_api, broker, "rotord/t", "rotord_t", "t"};
  const char* const cases[][2] = {
      {"goto", R"({"az": 200, "el": 30})"},
      {"goto", R"({"az": 9999})"},
      {"goto", "{nope"},
      {"move", R"({"dir": "cw", "hold_ms": 0})"},
      {"move", R"({"dir": "sideways"})"},
      {"stop", ""},
      {"park", "{}"},
      {"speed", R"({"speed_pct": 40})"},
      {"speed", R"({"speed_pct": 400})"},
      {"reset", "{}"},
      {"place", R"({"locator": "ZZ99"})"},
      {"preset", R"({"name": "EU"})"},
      {"preset", R"({"name": "JA"})"},
  };
  Millis now = 0;
  for (const auto& c : cases) {
    // A minute apart: no line is a repeat of the one before.
    now += CommandLog::kWindowMs;
    rest_log.poll(now);
    mqtt_log.poll(now);
    StringSink sink;
    session.receive(
        rotord::testing::post_request(std::string("/api/") + c[0], c[1], "application/json"), sink);
    bridge.on_message(std::string("rotord/t/cmd/") + c[0], c[1]);
  }
  ASSERT_EQ(rest_lines.lines.size(), std::size(cases));
  ASSERT_EQ(mqtt_lines.lines.size(), std::size(cases));
  for (std::size_t n = 0; n < std::size(cases); ++n) {
    std::string line = rest_lines.lines[n];
    line.replace(line.find("from rest"), 9, "from mqtt");
    EXPECT_EQ(mqtt_lines.lines[n], line);
  }
  EXPECT_EQ(rest_lines.lines[0], "command goto az 200.0 el 30.0 from rest (a network client): OK");
  EXPECT_EQ(rest_lines.lines[1], "command goto from rest (a network client): UNPROCESSABLE");
  EXPECT_EQ(rest_lines.lines[2], "command goto from rest (a network client): BAD REQUEST");
  EXPECT_EQ(rest_lines.lines[5], "command stop from rest (a network client): OK");

  // MQTT's own refusals are logged as well: mqtt.control off.
  mqtt_rotator.settings.set(SettingId::kMqttControl, 0);
  bridge.on_message("rotord/t/cmd/goto", R"({"az": 100})");
  EXPECT_EQ(mqtt_lines.lines.back(), "command goto from mqtt (a network client): DENIED");
}

// A tracker streaming go-tos every 100 ms for a minute: the first line, and
// one summary when the minute ends; the next minute starts again.
TEST_F(CommandLogTest, AStreamOfGoTosWritesTwoLinesAMinute) {
  const Origin gpredict{"rotctld", client(20)};
  Millis now = 0;
  for (int n = 0; n < 600; ++n, now += 100) {
    log.poll(now);
    go_to(*r.controller, gpredict, 100.0f + static_cast<float>(n) * 0.1f, 20.0f);
  }
  log.poll(now);
  const std::vector<std::string> want = {
      "command goto az 100.0 el 20.0 from rotctld (192.168.1.20): OK",
      "command goto from rotctld (192.168.1.20): OK, 599 more in the last minute",
  };
  EXPECT_EQ(out.lines, want);
  // A STOP in that minute is a line of its own, not a repeat.
  go_to(*r.controller, gpredict, 150.0f, 20.0f);
  stop(*r.controller, gpredict);
  ASSERT_EQ(out.lines.size(), 4u);
  EXPECT_EQ(out.lines[2], "command goto az 150.0 el 20.0 from rotctld (192.168.1.20): OK");
  EXPECT_EQ(out.lines[3], "command stop from rotctld (192.168.1.20): OK");
}

// Many clients at once: at most kLinesPerWindow lines a minute, the rest
// counted in one line at the minute's end; a fifth repeat sums up the oldest.
TEST_F(CommandLogTest, ManyClientsCannotFloodIt) {
  log.poll(0);
  for (std::uint32_t n = 0; n < 100; ++n) stop(*r.controller, {"wrc", client(n)});
  EXPECT_EQ(out.lines.size(), CommandLog::kLinesPerWindow);
  log.poll(CommandLog::kWindowMs);
  EXPECT_EQ(out.lines.back(),
            std::to_string(100 - CommandLog::kLinesPerWindow) +
                " more command lines in the last minute, over the command log's budget");
}

TEST_F(CommandLogTest, TheOldestRepeatGivesWayAndIsSummedUp) {
  log.poll(0);
  stop(*r.controller, {"wrc", client(1)});
  stop(*r.controller, {"wrc", client(1)});
  for (std::uint32_t n = 2; n <= CommandLog::kRepeats + 1; ++n)
    stop(*r.controller, {"wrc", client(n)});
  ASSERT_EQ(out.lines.size(), CommandLog::kRepeats + 2);
  EXPECT_EQ(out.lines[CommandLog::kRepeats],
            "command stop from wrc (192.168.1.1): OK, 1 more in the last minute");
}

// The buttons are a front end too: a press and a release, no client.
TEST_F(CommandLogTest, TheButtonsWriteTheirPressAndRelease) {
  ASSERT_EQ(r.settings.set(SettingId::kPinBtnCw, 13).error, Error::kOk);
  ASSERT_EQ(r.settings.set(SettingId::kPinBtnCcw, 4).error, Error::kOk);
  ASSERT_EQ(r.settings.set(SettingId::kButtonsEnabled, 1).error, Error::kOk);
  r.run_ms(100);
  r.az.button_fwd.on = true;
  r.run_ms(200);
  r.az.button_fwd.on = false;
  r.run_ms(200);
  const std::vector<std::string> want = {
      "command move az cw from buttons: OK",
      "command move az stop from buttons: OK",
  };
  EXPECT_EQ(out.lines, want);
}

TEST_F(CommandLogTest, WithoutAJournalNothingIsWritten) {
  r.controller->attach_journal(nullptr);
  EXPECT_EQ(go_to(*r.controller, {"rotctld", client(20)}, 120.0f, std::nullopt), Error::kOk);
  EXPECT_TRUE(out.lines.empty());
}

}  // namespace
}  // namespace rotord::command
