// The command layer (core/command/, issue 25): each command once, run by
// REST and MQTT alike. Proves the two front ends answer every command with
// the same status and the same body byte for byte (the layer decides, the
// front ends translate), that each REST command route takes its gate and
// help from the command's row, and the gate itself: the control lock,
// failed-closed access settings, STOP for everyone.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "command/commands.hpp"
#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "mqtt/bridge.hpp"
#include "mqtt_last_result.hpp"
#include "web/http_session.hpp"

namespace rotord::command {
namespace {

using rotord::testing::HttpResponse;
using rotord::testing::parse_responses;
using rotord::testing::StringSink;
using SettingId = settings::Id;

using rotord::testing::LastResult;

/// One rotator behind REST, an identical one behind MQTT.
struct TwoFrontEnds {
  TwoFrontEnds() {
    for (rotord::testing::FakeRotator* r : {&rest_rotator, &mqtt_rotator}) {
      r->settings.set(SettingId::kMqttControl, 1);
      r->settings.set_text(SettingId::kPreset1, "150:EU");
      r->settings.set(SettingId::kStationLatDeg, 52.0);
      r->settings.set(SettingId::kStationLonDeg, 13.0);
      r->run_ms(50);
    }
  }
  rotord::testing::FakeRotator rest_rotator;
  rotord::testing::FakeRotator mqtt_rotator;
  web::Api rest_api{web::ApiContext{*rest_rotator.controller, nullptr, nullptr, nullptr, "1"}};
  web::Api mqtt_api{web::ApiContext{*mqtt_rotator.controller, nullptr, nullptr, nullptr, "1"}};
  web::HttpSession session{rest_api};
  LastResult transport;
  mqtt::Bridge bridge{mqtt_api, transport, "rotord/t", "rotord_t", "t"};

  HttpResponse rest(const std::string& name, const std::string& body) {
    StringSink sink;
    session.receive(rotord::testing::post_request("/api/" + name, body, "application/json"), sink);
    const std::vector<HttpResponse> rs = parse_responses(sink.data);
    return rs.empty() ? HttpResponse{} : rs[0];
  }
  std::string mqtt(const std::string& name, const std::string& body) {
    transport.result.clear();
    bridge.on_message("rotord/t/cmd/" + name, body);
    return transport.result;
  }
  void run_ms(Millis ms) {
    rest_rotator.run_ms(ms);
    mqtt_rotator.run_ms(ms);
  }
};

struct Case {
  const char* name;
  const char* body;
};

// Every command, done and refused in each way its arguments can be wrong.
constexpr Case kCases[] = {
    {"goto", R"({"az": 200})"},
    {"goto", R"({"az": 200, "el": 30})"},
    {"goto", R"({"az": 9999})"},
    {"goto", R"({"el": 170})"},
    {"goto", R"({"az": "north"})"},
    {"goto", "{nope"},
    {"goto", "{}"},
    {"goto", R"({"azz": 1})"},
    {"move", R"({"dir": "cw", "hold_ms": 0})"},
    {"move", R"({"dir": "sideways"})"},
    {"move", R"({"dir": "up", "axis": "az"})"},
    {"move", R"({"dir": "cw", "speed": 500})"},
    {"move", R"({"dir": "cw", "hold_ms": 50})"},
    {"move", R"({"axis": "el", "dir": "stop"})"},
    {"move", "{}"},
    {"stop", ""},
    {"park", "{}"},
    {"speed", R"({"speed_pct": 40})"},
    {"speed", R"({"speed_pct": 400})"},
    {"speed", "{}"},
    {"reset", "{}"},
    {"place", R"({"locator": "FN31"})"},
    {"place", R"({"locator": "FN31", "path": "long"})"},
    {"place", R"({"locator": "ZZ99"})"},
    {"place", R"({"lat": 10})"},
    {"place", R"({"city": "Berlin"})"},
    {"preset", R"({"name": "EU"})"},
    {"preset", R"({"name": "JA"})"},
    {"preset", R"({"az": 3})"},
};

TEST(CommandLayer, RestAndMqttAnswerEveryCommandAlike) {
  TwoFrontEnds f;
  std::set<int> statuses;
  for (const Case& c : kCases) {
    const HttpResponse rest = f.rest(c.name, c.body);
    statuses.insert(rest.status);
    const std::string mqtt = f.mqtt(c.name, c.body);
    const std::string expected = std::string(R"({"cmd":")") + c.name + R"(","status":)" +
                                 std::to_string(rest.status) + R"(,"response":)" + rest.body + "}";
    EXPECT_EQ(mqtt, expected) << c.name << " " << c.body;
    f.run_ms(100);
    const RotatorStatus a = f.rest_rotator.controller->status();
    const RotatorStatus b = f.mqtt_rotator.controller->status();
    EXPECT_EQ(a.mode, b.mode) << c.name << " " << c.body;
    EXPECT_EQ(a.az.has_target, b.az.has_target) << c.name << " " << c.body;
    EXPECT_EQ(a.az.target_deg, b.az.target_deg) << c.name << " " << c.body;
  }
  // Done, unreadable, unknown and out of range each occur above.
  EXPECT_EQ(statuses, (std::set<int>{200, 400, 404, 422}));
}

TEST(CommandLayer, ALatchedFaultReadsTheSameForEveryCommandThatMoves) {
  TwoFrontEnds f;
  f.rest_rotator.az.adc.counts = 0;  // the wiper at the rail: a sensor fault
  f.mqtt_rotator.az.adc.counts = 0;
  f.run_ms(500);
  ASSERT_NE(f.rest_rotator.controller->status().az.fault, AxisFault::kNone);
  const std::string fault =
      R"({"error":"an axis has a latched fault: clear it with POST /api/reset"})";
  for (const Case& c :
       {Case{"goto", R"({"az": 200})"}, Case{"park", "{}"}, Case{"move", R"({"dir": "cw"})"},
        Case{"place", R"({"locator": "FN31"})"}}) {
    const HttpResponse rest = f.rest(c.name, c.body);
    EXPECT_EQ(rest.status, 409) << c.name;
    EXPECT_EQ(rest.body, fault) << c.name;
    EXPECT_EQ(f.mqtt(c.name, c.body),
              std::string(R"({"cmd":")") + c.name + R"(","status":409,"response":)" + fault + "}");
  }
}

TEST(CommandLayer, EachRestCommandRouteIsTheCommandsRow) {
  for (const Def& d : Commands::table()) {
    EXPECT_EQ(&Commands::def(d.id), &d) << d.name;  // the table is in the order of Id
    EXPECT_EQ(Commands::find(d.name), &d);
    const std::string path = "/api/" + std::string(d.name);
    const web::Api::Route* row = nullptr;
    for (const web::Api::Route& r : web::Api::routes())
      if (r.post && r.path == path) row = &r;
    ASSERT_NE(row, nullptr) << path;
    EXPECT_EQ(row->need, d.gate.need) << path;
    EXPECT_EQ(row->locked, d.gate.locked) << path;
    EXPECT_EQ(row->help, d.help) << path;
  }
  EXPECT_EQ(Commands::find("mode"), nullptr);  // a REST alias (idle = stop), not a command
}

TEST(CommandLayer, TheGate) {
  rotord::testing::FakeRotator r;
  Commands commands(*r.controller);
  const Authority anyone{Need::kControl, false};
  const Authority holder{Need::kControl, true};
  EXPECT_TRUE(commands.admit(Commands::def(Id::kGoto).gate, anyone).ok());
  EXPECT_EQ(commands.admit(Commands::def(Id::kGoto).gate, {Need::kRead, false}).status,
            Status::kForbidden);
  // The control lock: only its holder, but STOP for everyone.
  access::LockHolder who;
  who.key[0] = 7;
  r.controller->control_lock().take(who, 60'000);
  commands.poll(0);
  const Result locked = commands.run(Id::kGoto, {anyone, {}, R"({"az": 200})"});
  EXPECT_EQ(locked.status, Status::kLocked);
  EXPECT_STREQ(locked.message,
               "another operator holds the control lock (a web session, 60 s left); STOP still "
               "works");
  EXPECT_EQ(http_status(locked.status), 423);
  EXPECT_TRUE(commands.run(Id::kGoto, {holder, {}, R"({"az": 200})"}).ok());
  EXPECT_TRUE(commands.run(Id::kStop, {{Need::kPublic, false}, {}, "junk"}).ok());
  EXPECT_EQ(r.controller->status().mode, Mode::kIdle);
}

}  // namespace
}  // namespace rotord::command
