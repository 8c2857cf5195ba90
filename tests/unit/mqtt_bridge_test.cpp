// The portable MQTT bridge on a controller with fake hardware: topics, the
// state on change and while moving, commands through the command layer the
// REST API runs too (same errors), mqtt.control, STOP always, discovery messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "fake_rotator.hpp"
#include "json/json_reader.hpp"
#include "mqtt/bridge.hpp"
#include "mqtt/topics.hpp"

namespace rotord::mqtt {
namespace {

using settings::Id;

/// The transport boundary: records what the bridge publishes.
class RecordingTransport final : public Transport {
 public:
  struct Message {
    std::string topic, payload;
    bool retain;
  };
  bool up = true;
  int room = -1;  ///< publishes still taken before the queue is "full"; -1: no limit
  std::vector<Message> sent;
  bool connected() const override { return up; }
  bool publish(std::string_view topic, std::string_view payload, bool retain) override {
    if (!up || room == 0) return false;
    if (room > 0) --room;
    sent.push_back({std::string(topic), std::string(payload), retain});
    return true;
  }
  std::vector<Message> on(const std::string& topic) const {
    std::vector<Message> out;
    for (const Message& m : sent)
      if (m.topic == topic) out.push_back(m);
    return out;
  }
};

TEST(MqttTopics, PrefixDefaultsToTheHostName) {
  char buf[kMaxPrefixBytes + 1];
  EXPECT_EQ(std::string(buf, make_prefix("", "shack-pi", buf, sizeof buf)), "rotord/shack-pi");
  EXPECT_EQ(std::string(buf, make_prefix("station/hf", "x", buf, sizeof buf)), "station/hf");
  EXPECT_EQ(make_prefix("a/+/b", "x", buf, sizeof buf), 0u);
  EXPECT_EQ(make_prefix("a/#", "x", buf, sizeof buf), 0u);
  EXPECT_EQ(make_prefix("/a", "x", buf, sizeof buf), 0u);
  EXPECT_EQ(make_prefix("a/", "x", buf, sizeof buf), 0u);
  EXPECT_EQ(make_prefix("a//b", "x", buf, sizeof buf), 0u);
  EXPECT_EQ(make_prefix("a b", "x", buf, sizeof buf), 0u);
}

TEST(MqttTopics, CommandNames) {
  EXPECT_EQ(command_name("rotord/a", "rotord/a/cmd/goto"), "goto");
  EXPECT_EQ(command_name("rotord/a", "rotord/ab/cmd/goto"), "");
  EXPECT_EQ(command_name("rotord/a", "rotord/a/cmd/"), "");
  EXPECT_EQ(command_name("rotord/a", "rotord/a/cmd/x/y"), "");
  EXPECT_EQ(command_name("rotord/a", "rotord/a/state"), "");
  char id[16];
  EXPECT_EQ(std::string(id, make_node_id("rotord-a.b c", id, sizeof id)), "rotord-a_b_c");
}

class MqttBridge : public ::testing::Test {
 protected:
  MqttBridge() { r.run_ms(50); }
  rotord::testing::FakeRotator r;
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "9.9.9"}};
  RecordingTransport transport;
  Bridge bridge{api, transport, "rotord/test", "rotord_test", "rotord test"};

  std::string last_result() const {
    const auto results = transport.on("rotord/test/result");
    return results.empty() ? std::string() : results.back().payload;
  }
  void command(const std::string& name, const std::string& body) {
    bridge.on_message("rotord/test/cmd/" + name, body);
  }
};

TEST_F(MqttBridge, StateIsRetainedOnConnectAndOnChange) {
  bridge.poll(0);
  auto states = transport.on("rotord/test/state");
  ASSERT_EQ(states.size(), 1u);
  EXPECT_TRUE(states[0].retain);
  EXPECT_TRUE(web::JsonObjectReader(states[0].payload).valid()) << states[0].payload;
  EXPECT_NE(states[0].payload.find(R"("mode":"idle")"), std::string::npos);
  // Nothing changed: nothing more, however long.
  bridge.poll(5000);
  EXPECT_EQ(transport.on("rotord/test/state").size(), 1u);
  r.controller->set_speed_pct(30);
  bridge.poll(5100);
  EXPECT_EQ(transport.on("rotord/test/state").size(), 2u);
}

TEST_F(MqttBridge, StateAtTheSetRateWhileMoving) {
  r.settings.set(Id::kMqttStateHz, 2);
  api.controller().settings().set(Id::kMqttControl, 1);
  bridge.poll(0);
  command("goto", R"({"az": 300})");
  EXPECT_NE(last_result().find(R"("status":200)"), std::string::npos) << last_result();
  const std::size_t before = transport.on("rotord/test/state").size();
  r.run_ms(100);
  ASSERT_TRUE(r.controller->status().moving());
  // Controller time stands still from here: only the rate publishes.
  bridge.poll(100);  // the goto changed the mode and target: published
  const std::size_t changed = transport.on("rotord/test/state").size();
  EXPECT_EQ(changed, before + 1);
  bridge.poll(300);  // 200 ms later: not yet (2 Hz)
  EXPECT_EQ(transport.on("rotord/test/state").size(), changed);
  bridge.poll(600);
  EXPECT_EQ(transport.on("rotord/test/state").size(), changed + 1);
}

TEST_F(MqttBridge, CommandsNeedMqttControlButStopIsAlwaysObeyed) {
  bridge.poll(0);
  command("goto", R"({"az": 200})");
  EXPECT_NE(last_result().find(R"("status":403)"), std::string::npos) << last_result();
  EXPECT_NE(last_result().find("mqtt.control is off"), std::string::npos);
  EXPECT_FALSE(r.controller->status().moving());

  api.controller().settings().set(Id::kMqttControl, 1);
  command("goto", R"({"az": 200})");
  EXPECT_EQ(
      last_result(),
      R"({"cmd":"goto","status":200,"response":{"ok":true,"az_target":200,"el_target":null}})");
  r.run_ms(100);
  EXPECT_TRUE(r.controller->status().moving());

  api.controller().settings().set(Id::kMqttControl, 0);
  command("stop", "");
  EXPECT_EQ(last_result(), R"({"cmd":"stop","status":200,"response":{"ok":true}})");
  EXPECT_EQ(r.controller->status().mode, Mode::kIdle);
}

TEST_F(MqttBridge, ErrorsAreTheRestApis) {
  api.controller().settings().set(Id::kMqttControl, 1);
  command("goto", R"({"az": "north"})");
  EXPECT_EQ(last_result(),
            R"({"cmd":"goto","status":400,"response":{"error":"az must be a number"}})");
  command("goto", "{nope");
  EXPECT_NE(last_result().find(R"("status":400,"response":{"error":"invalid JSON)"),
            std::string::npos)
      << last_result();
  command("speed", R"({"speed_pct": 500})");
  EXPECT_NE(last_result().find(R"("status":422)"), std::string::npos) << last_result();
  command("fly", "{}");
  EXPECT_NE(last_result().find(R"("cmd":"fly","status":404)"), std::string::npos);
  bridge.on_message("rotord/test/cmd/stop", "{}", true);
  EXPECT_NE(last_result().find(R"("status":413)"), std::string::npos);
  const std::size_t results = transport.on("rotord/test/result").size();
  bridge.on_message("other/topic", "{}");
  EXPECT_EQ(transport.on("rotord/test/result").size(), results);
}

TEST_F(MqttBridge, AFullQueueDelaysTheAnnouncementsNeverLosesThem) {
  // A client with room for two messages per pass (the Pico's lwIP ring
  // buffer): discovery, info and the state all go out, in order, each once.
  for (Millis t = 0; t < 1000; t += 10) {
    transport.room = 2;
    bridge.poll(t);
  }
  std::vector<std::string> topics;
  for (const auto& m : transport.sent) topics.push_back(m.topic);
  std::vector<std::string> expected = {
      "homeassistant/sensor/rotord_test/azimuth/config",
      "homeassistant/sensor/rotord_test/elevation/config",
      "homeassistant/number/rotord_test/target_azimuth/config",
      "homeassistant/button/rotord_test/stop/config",
      "homeassistant/button/rotord_test/park/config",
      "homeassistant/binary_sensor/rotord_test/fault/config",
      "homeassistant/sensor/rotord_test/mechanical_azimuth/config"};
  // Then one button config per preset slot (empty for an unused one).
  for (int n = 1; n <= 16; ++n)
    expected.push_back("homeassistant/button/rotord_test/preset_" + std::to_string(n) + "/config");
  // Then the wear odometer's and the slips' sensors of each axis (docs/care.md).
  for (const char* axis : {"az", "el"})
    for (const char* count : {"starts", "reversals", "run_time", "turned", "brake_cycles",
                              "relay_switchings", "faults", "slips"})
      expected.push_back(std::string("homeassistant/sensor/rotord_test/") + axis + "_" + count +
                         "/config");
  expected.push_back("rotord/test/info");
  expected.push_back("rotord/test/state");
  EXPECT_EQ(topics, expected);
}

TEST_F(MqttBridge, TheStateFitsItsBuffer) {
  // The Pico's MQTT output buffer is sized from this (lwip_mqtt_opts.h).
  bridge.poll(0);
  const auto state = transport.on("rotord/test/state");
  ASSERT_EQ(state.size(), 1u);
  EXPECT_LT(state[0].payload.size(), Bridge::kMaxStateBytes);
  std::size_t longest_discovery = 0;
  for (const auto& m : transport.sent)
    if (m.topic.rfind("homeassistant/", 0) == 0)
      longest_discovery = std::max(longest_discovery, m.payload.size());
  EXPECT_LT(longest_discovery, Bridge::kMaxDiscoveryBytes);
  RecordProperty("state_bytes", static_cast<int>(state[0].payload.size()));
  RecordProperty("longest_discovery_bytes", static_cast<int>(longest_discovery));
}

TEST_F(MqttBridge, AWebPasswordDoesNotStopTheBrokersCommands) {
  // A broker message carries no login: mqtt.control and the broker's ACLs
  // are its authority, whether or not the web asks for a password.
  const std::string salt(32, '0'), key(32, '1');
  ASSERT_EQ(api.controller()
                .settings()
                .set_text(Id::kWebPassword, "pbkdf2-sha256$1000$" + salt + "$" + key)
                .error,
            Error::kOk);
  api.controller().settings().set(Id::kMqttControl, 1);
  command("goto", R"({"az": 200})");
  EXPECT_EQ(
      last_result(),
      R"({"cmd":"goto","status":200,"response":{"ok":true,"az_target":200,"el_target":null}})");
  command("speed", R"({"speed_pct": 500})");
  EXPECT_NE(last_result().find(R"("status":422)"), std::string::npos) << last_result();
  command("stop", "");
  EXPECT_EQ(last_result(), R"({"cmd":"stop","status":200,"response":{"ok":true}})");
}

TEST_F(MqttBridge, TheAllowListAppliesToTheBrokersAddress) {
  api.controller().settings().set(Id::kMqttControl, 1);
  ASSERT_EQ(
      api.controller().settings().set_text(Id::kAccessControlNetworks, "192.168.1.0/24").error,
      Error::kOk);
  // Not told where the broker is: read-only while the list is set.
  command("goto", R"({"az": 200})");
  EXPECT_EQ(last_result(),
            R"({"cmd":"goto","status":403,"response":{"error":"read-only: the broker's address )"
            R"(is not in access.control_networks"}})");
  bridge.set_broker_peer(access::Peer::from_ipv4(0x0A000001));  // 10.0.0.1
  command("park", "{}");
  EXPECT_NE(last_result().find(R"("status":403)"), std::string::npos) << last_result();
  r.run_ms(100);
  EXPECT_FALSE(r.controller->status().moving());
  command("stop", "");  // STOP always
  EXPECT_EQ(last_result(), R"({"cmd":"stop","status":200,"response":{"ok":true}})");
  bridge.set_broker_peer(access::Peer::from_ipv4(0xC0A80105));  // 192.168.1.5
  command("goto", R"({"az": 200})");
  EXPECT_NE(last_result().find(R"("status":200)"), std::string::npos) << last_result();
}

TEST_F(MqttBridge, TheControlLockRefusesTheBroker) {
  api.controller().settings().set(Id::kMqttControl, 1);
  access::LockHolder holder;
  holder.key[0] = 1;
  api.controller().control_lock().take(holder, 1'000'000);
  command("goto", R"({"az": 200})");
  EXPECT_NE(last_result().find(R"("cmd":"goto","status":423)"), std::string::npos) << last_result();
  command("stop", "");
  EXPECT_EQ(last_result(), R"({"cmd":"stop","status":200,"response":{"ok":true}})");
}

TEST_F(MqttBridge, DiscoveryOnConnectAndAgainAfterAReconnect) {
  bridge.poll(0);
  const auto az = transport.on("homeassistant/sensor/rotord_test/azimuth/config");
  ASSERT_EQ(az.size(), 1u);
  EXPECT_TRUE(az[0].retain);
  EXPECT_TRUE(web::JsonObjectReader(az[0].payload).valid()) << az[0].payload;
  EXPECT_NE(az[0].payload.find(R"("state_topic":"rotord/test/state")"), std::string::npos);
  EXPECT_EQ(transport.on("homeassistant/button/rotord_test/stop/config").size(), 1u);
  EXPECT_EQ(transport.on("homeassistant/button/rotord_test/park/config").size(), 1u);
  EXPECT_EQ(transport.on("homeassistant/number/rotord_test/target_azimuth/config").size(), 1u);
  EXPECT_EQ(transport.on("homeassistant/binary_sensor/rotord_test/fault/config").size(), 1u);
  transport.up = false;
  bridge.poll(1000);
  transport.up = true;
  bridge.poll(2000);
  EXPECT_EQ(transport.on("homeassistant/sensor/rotord_test/azimuth/config").size(), 2u);
  EXPECT_EQ(transport.on("rotord/test/state").size(), 2u);
}

}  // namespace
}  // namespace rotord::mqtt

namespace rotord::mqtt {
namespace {

TEST_F(MqttBridge, StationListsTheRotordsSeen) {
  Station station;
  bridge.set_station(&station);
  bridge.poll(0);
  // Our own state, as the broker echoes it back, and another rotord's.
  const std::string own = transport.on("rotord/test/state").back().payload;
  bridge.on_message("rotord/test/availability", "online");  // before the state
  bridge.on_message("rotord/test/state", own);
  bridge.on_message("rotord/other/info",
                    R"({"rotord":"0.1.0","name":"rotord other","web":"http://other:8080/"})");
  bridge.on_message(
      "rotord/other/state",
      R"({"version":"0.1.0","mode":"goto","fault":false,"az":{"position_deg":271.5},"el":null})");
  bridge.on_message("zigbee2mqtt/lamp/state", R"({"state":"ON"})");
  bridge.on_message("rotord/evil/info",
                    R"j({"rotord":"1","name":"x","web":"javascript:alert(1)"})j");
  bridge.on_message("rotord/evil/state",
                    R"({"version":"0.1.0","mode":"idle","az":{"position_deg":1}})");
  std::string json;
  class Sink final : public protocol::ByteSink {
   public:
    explicit Sink(std::string& s) : s_(s) {}
    void write(std::string_view b) override { s_.append(b); }
    std::string& s_;
  } sink(json);
  {
    web::JsonWriter w(sink);
    station.write_station(w);
  }
  EXPECT_EQ(station.size(), 3u) << json;
  EXPECT_NE(json.find(R"("prefix":"rotord/evil","name":"x","web":"")"), std::string::npos) << json;
  EXPECT_EQ(json.find("javascript"), std::string::npos);
  EXPECT_NE(
      json.find(
          R"({"prefix":"rotord/test","name":"","web":"","online":true,"mode":"idle","az_deg":100,"mech_az_deg":100,"el_deg":20,"fault":false})"),
      std::string::npos)
      << json;
  EXPECT_NE(
      json.find(
          R"({"prefix":"rotord/other","name":"rotord other","web":"http://other:8080/","online":false,"mode":"goto","az_deg":271.5,"mech_az_deg":271.5,"el_deg":null,"fault":false})"),
      std::string::npos)
      << json;
}

}  // namespace
}  // namespace rotord::mqtt

namespace rotord::mqtt {
namespace {

// The rotator's own entities, byte for byte as Home Assistant receives them
// (publish_discovery split into functions of at most 60 lines, issue 25:
// the payloads are the ones the single function published). The device
// head every entity shares is written once here.
TEST_F(MqttBridge, TheRotatorsEntitiesAreByteForByteAsBefore) {
  bridge.poll(0);
  const std::string device =
      R"("availability_topic":"rotord/test/availability","payload_available":"online",)"
      R"("payload_not_available":"offline","device":{"identifiers":["rotord_test"],)"
      R"("name":"rotord test","manufacturer":"rotord",)"
      R"("model":"rotord antenna rotator controller","sw_version":""},)";
  struct Expected {
    const char* topic;
    const char* head;  // name and unique_id
    const char* body;  // after the device
  };
  const Expected expected[] = {
      {"sensor/rotord_test/azimuth", R"({"name":"Azimuth","unique_id":"rotord_test_azimuth",)",
       R"("state_topic":"rotord/test/state","value_template":"{{ value_json.beam.az_deg | round(1) }}","unit_of_measurement":"°","state_class":"measurement","icon":"mdi:compass"})"},
      {"sensor/rotord_test/elevation",
       R"({"name":"Elevation","unique_id":"rotord_test_elevation",)",
       R"("state_topic":"rotord/test/state","value_template":"{{ value_json.beam.el_deg | round(1) }}","unit_of_measurement":"°","state_class":"measurement","icon":"mdi:compass"})"},
      {"number/rotord_test/target_azimuth",
       R"({"name":"Target azimuth","unique_id":"rotord_test_target_azimuth",)",
       R"("command_topic":"rotord/test/cmd/goto","command_template":"{\"az\": {{ value }}}","state_topic":"rotord/test/state","value_template":"{{ value_json.az.target_deg if value_json.az.target_deg is not none else value_json.az.position_deg }}","min":0,"max":450,"step":1,"mode":"box","unit_of_measurement":"°"})"},
      {"button/rotord_test/stop", R"({"name":"Stop","unique_id":"rotord_test_stop",)",
       R"("command_topic":"rotord/test/cmd/stop","payload_press":"{}"})"},
      {"button/rotord_test/park", R"({"name":"Park","unique_id":"rotord_test_park",)",
       R"("command_topic":"rotord/test/cmd/park","payload_press":"{}"})"},
      {"binary_sensor/rotord_test/fault", R"({"name":"Fault","unique_id":"rotord_test_fault",)",
       R"("state_topic":"rotord/test/state","value_template":"{{ 'ON' if value_json.fault else 'OFF' }}","device_class":"problem"})"},
      {"sensor/rotord_test/mechanical_azimuth",
       R"({"name":"Mechanical azimuth","unique_id":"rotord_test_mechanical_azimuth",)",
       R"("state_topic":"rotord/test/state","value_template":"{{ value_json.az.position_deg | round(1) }}","unit_of_measurement":"°","state_class":"measurement","icon":"mdi:compass"})"},
  };
  for (const Expected& e : expected) {
    const auto sent = transport.on(std::string("homeassistant/") + e.topic + "/config");
    ASSERT_EQ(sent.size(), 1u) << e.topic;
    EXPECT_EQ(sent[0].payload, std::string(e.head) + device + e.body) << e.topic;
  }
}

// An azimuth-only rotator removes the elevation sensor (an empty retained
// config) and announces the others as before.
TEST(MqttBridgeAzOnly, TheElevationSensorIsRemoved) {
  rotord::testing::FakeRotator r{false};
  r.run_ms(50);
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "9.9.9"}};
  RecordingTransport transport;
  Bridge bridge{api, transport, "rotord/test", "rotord_test", "rotord test"};
  bridge.poll(0);
  const auto el = transport.on("homeassistant/sensor/rotord_test/elevation/config");
  ASSERT_EQ(el.size(), 1u);
  EXPECT_TRUE(el[0].retain);
  EXPECT_EQ(el[0].payload, "");
  const auto az = transport.on("homeassistant/sensor/rotord_test/azimuth/config");
  ASSERT_EQ(az.size(), 1u);
  EXPECT_NE(az[0].payload.find(R"("value_template":"{{ value_json.beam.az_deg | round(1) }}")"),
            std::string::npos);
}

}  // namespace
}  // namespace rotord::mqtt
