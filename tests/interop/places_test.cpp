// Where the beam points (issue 26) through the real daemon: turning to a
// locator or a position over REST (curl-free: the test's own HTTP client on a
// real socket), the console on its pseudo-terminal (socat as the terminal),
// and MQTT on a real Mosquitto (mosquitto_rr); presets kept across a restart;
// every refusal names its reason. The expected bearings are computed here
// with the spherical law of cosines and atan2 (not the core's haversine code).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "mosquitto_broker.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The initial great-circle bearing, computed independently of the core.
double bearing_deg(double lat1, double lon1, double lat2, double lon2) {
  const double d = kPi / 180.0;
  const double y = std::sin((lon2 - lon1) * d) * std::cos(lat2 * d);
  const double x = std::cos(lat1 * d) * std::sin(lat2 * d) -
                   std::sin(lat1 * d) * std::cos(lat2 * d) * std::cos((lon2 - lon1) * d);
  return std::fmod(std::atan2(y, x) / d + 360.0, 360.0);
}

double wrap360(double v) {
  return std::fmod(std::fmod(v, 360.0) + 360.0, 360.0);
}

class Places : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = make_temp_dir("rotord-places");
    config = dir + "/settings.json";
    // JO62QM's centre (Berlin): 52.5208 N, 13.375 E.
    std::ofstream(config) << R"({"station.lat_deg": 52.520833, "station.lon_deg": 13.375})"
                          << "\n";
  }
  void TearDown() override {
    daemon.reset();
    std::filesystem::remove_all(dir);
  }
  void start(std::vector<std::string> extra = {}) {
    std::vector<std::string> args{"--sim", "g5500", "--clock", "manual", "--config", config};
    args.insert(args.end(), extra.begin(), extra.end());
    daemon = std::make_unique<DaemonProcess>(args);
    ASSERT_TRUE(daemon->ready()) << daemon->output();
  }
  HttpResponse get(const std::string& path) { return http(daemon->ports().web, "GET", path); }
  HttpResponse post(const std::string& path, const std::string& body) {
    return http(daemon->ports().web, "POST", path, body);
  }
  double az_target() {
    const std::string s = get("/api/status").body;
    return json_number(s, "target_deg", s.find("\"az\":{"));
  }

  std::string dir, config;
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(Places, BearingShownFirstThenTurnShortAndLongPath) {
  start();
  // FN31PR's centre: 41.729167 N, 72.708333 W.
  const double expected = bearing_deg(52.520833, 13.375, 41.729167, -72.708333);
  HttpResponse r = get("/api/place?locator=fn31pr");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NEAR(json_number(r.body, "bearing_deg"), expected, 0.01) << r.body;
  EXPECT_NE(r.body.find(R"("locator":"FN31PR")"), std::string::npos) << r.body;
  EXPECT_NEAR(json_number(r.body, "distance_km"), 6227, 5) << r.body;  // Berlin-Hartford
  // A preview moves nothing.
  EXPECT_NE(get("/api/status").body.find(R"("target_deg":null)"), std::string::npos);

  r = post("/api/place", R"({"locator": "FN31PR"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NEAR(wrap360(az_target()), expected, 0.05);
  r = post("/api/place", R"({"lat": 41.729167, "lon": -72.708333, "path": "long"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NEAR(wrap360(az_target()), wrap360(expected + 180.0), 0.05);
  EXPECT_NE(r.body.find(R"("path":"long")"), std::string::npos) << r.body;
  // The beam follows once the rotator has arrived.
  ASSERT_GE(daemon->advance_ms(120000), 0);
  const std::string s = get("/api/status").body;
  EXPECT_NEAR(json_number(s, "az_deg", s.find("\"beam\":")), wrap360(expected + 180.0), 1.5) << s;
}

TEST_F(Places, BadPlacesAreRefusedWithTheReasonAndNothingMoves) {
  start();
  HttpResponse r = get("/api/place?locator=ZZ99");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("not a Maidenhead locator"), std::string::npos) << r.body;
  r = post("/api/place", R"({"locator": "JO6"})");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("4, 6, 8 or 10 characters"), std::string::npos) << r.body;
  r = post("/api/place", R"({"lat": 91, "lon": 0})");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("latitude is outside -90..90"), std::string::npos) << r.body;
  r = get("/api/place?lat=10&lon=-181");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("longitude is outside -180..180"), std::string::npos) << r.body;
  r = post("/api/place", R"({"locator": "FN31PR", "path": "sideways"})");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("short or long"), std::string::npos) << r.body;
  // A travel of 0..180: the west is out of reach, and the refusal says so.
  ASSERT_EQ(post("/api/settings", R"({"az.min_deg": 0, "az.max_deg": 180})").status, 200);
  ASSERT_GE(daemon->advance_ms(100), 0);  // the controller takes them on its next tick
  r = get("/api/place?locator=FN31PR");
  EXPECT_NE(r.body.find(R"("reachable":false)"), std::string::npos) << r.body;
  r = post("/api/place", R"({"locator": "FN31PR"})");
  EXPECT_EQ(r.status, 422);
  EXPECT_NE(r.body.find("is outside the travel 0..180"), std::string::npos) << r.body;
  EXPECT_NE(get("/api/status").body.find(R"("target_deg":null)"), std::string::npos);
}

TEST_F(Places, PresetsAreKeptAcrossARestartAndLimited) {
  start();
  HttpResponse r = post("/api/presets", R"({"name": "EU", "az": 45})");
  ASSERT_EQ(r.status, 200) << r.body;
  r = post("/api/presets", R"({"name": "JA LP", "az": 150, "long_path": true})");
  ASSERT_EQ(r.status, 200) << r.body;
  r = post("/api/presets", R"({"name": "a name of twenty-one b", "az": 10})");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("at most 20 bytes"), std::string::npos) << r.body;
  r = post("/api/presets", R"({"name": "X", "az": 400})");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.find("az is outside 0..360"), std::string::npos) << r.body;
  for (int n = 3; n <= 16; ++n)
    ASSERT_EQ(post("/api/presets", R"({"name": "P)" + std::to_string(n) + R"(", "az": 10})").status,
              200);
  r = post("/api/presets", R"({"name": "P17", "az": 10})");
  EXPECT_EQ(r.status, 409);
  EXPECT_NE(r.body.find("16 presets already"), std::string::npos) << r.body;
  // Replacing one by its name is not a 17th.
  EXPECT_EQ(post("/api/presets", R"({"name": "P16", "az": 20})").status, 200);

  daemon.reset();  // SIGTERM: a restart
  start();
  r = get("/api/presets");
  ASSERT_EQ(r.status, 200);
  EXPECT_NE(r.body.find(R"({"slot":1,"name":"EU","az_deg":45,"long_path":false})"),
            std::string::npos)
      << r.body;
  EXPECT_NE(r.body.find(R"("name":"JA LP","az_deg":150,"long_path":true)"), std::string::npos);
  EXPECT_NE(r.body.find(R"("name":"P16","az_deg":20)"), std::string::npos);
  r = post("/api/preset", R"({"name": "ja lp"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NEAR(wrap360(az_target()), 150, 0.01);
  EXPECT_EQ(post("/api/preset", R"({"name": "nowhere"})").status, 404);
  EXPECT_EQ(post("/api/presets/delete", R"({"name": "EU"})").status, 200);
  EXPECT_EQ(get("/api/presets").body.find(R"("name":"EU")"), std::string::npos);
}

TEST_F(Places, TheConsoleShowsTheBearingTurnsAndUsesPresets) {
  const std::string link = dir + "/console";
  start({"--pty", "console:" + link});
  const auto type = [&](const std::string& line) {
    return run_command("printf '%s\\n' '" + line + "' | timeout 10 socat -t2 - " + link +
                       ",raw,echo=0")
        .out;
  };
  const double expected = bearing_deg(52.520833, 13.375, 41.729167, -72.708333);
  char want[64];
  std::snprintf(want, sizeof want, "ok bearing %.1f deg, ", expected);
  EXPECT_NE(type("bearing FN31PR").find(want), std::string::npos);
  EXPECT_NE(get("/api/status").body.find(R"("target_deg":null)"), std::string::npos);
  std::snprintf(want, sizeof want, "ok turning to %.1f deg (", wrap360(expected + 180.0));
  EXPECT_NE(type("turn 41.729167, -72.708333 long").find(want), std::string::npos);
  EXPECT_NEAR(wrap360(az_target()), wrap360(expected + 180.0), 0.05);
  EXPECT_EQ(type("turn JO6"), "error: a locator has 4, 6, 8 or 10 characters (e.g. JO62QM)\r\n");
  EXPECT_EQ(type("turn 95 10"), "error: latitude is outside -90..90\r\n");
  EXPECT_EQ(type("set preset.3 300:W"), "ok preset.3=300:W\r\n");
  EXPECT_EQ(type("presets"), "preset.3 300.0 W\r\nok 1 of 16 presets\r\n");
  EXPECT_EQ(type("preset w"), "ok turning to W, 300.0 deg\r\n");
  EXPECT_NEAR(wrap360(az_target()), 300, 0.01);
  EXPECT_NE(type("set preset.4 400:X").find("error: preset.4: the heading is outside 0..360"),
            std::string::npos);
}

TEST_F(Places, MqttTurnsToAPlaceAndAPresetAndAnnouncesPresetButtons) {
  const std::string port = std::to_string(free_port());
  MosquittoBroker broker(dir, "127.0.0.1", std::stoi(port), "allow_anonymous true\n", "-p " + port);
  std::ofstream(config) << R"({"station.lat_deg": 52.520833, "station.lon_deg": 13.375,)"
                        << R"("mqtt.enabled": true, "mqtt.host": "127.0.0.1", "mqtt.port": )"
                        << port
                        << R"(, "mqtt.prefix": "rotord/test", "mqtt.client_id": "rotord-test",)"
                        << R"("mqtt.control": true, "preset.1": "45:EU"})"
                        << "\n";
  start();
  ASSERT_TRUE(daemon->wait_for_output("mqtt: connected")) << daemon->output();
  const auto command = [&](const std::string& name, const std::string& body) {
    return run_command("mosquitto_rr -p " + port + " -t rotord/test/cmd/" + name +
                       " -e rotord/test/result -W 10 -m '" + body + "' 2>&1")
        .out;
  };
  std::string r = command("place", R"({"locator": "FN31PR"})");
  EXPECT_NE(r.find(R"("cmd":"place","status":200)"), std::string::npos) << r;
  EXPECT_NEAR(wrap360(az_target()), bearing_deg(52.520833, 13.375, 41.729167, -72.708333), 0.05);
  r = command("place", R"({"locator": "AA"})");
  EXPECT_NE(r.find(R"("status":400)"), std::string::npos) << r;
  r = command("preset", R"({"name": "EU"})");
  EXPECT_NE(r.find(R"("cmd":"preset","status":200)"), std::string::npos) << r;
  EXPECT_NEAR(wrap360(az_target()), 45, 0.01);
  // Home Assistant's button for the preset, and the beam in the state.
  const std::string button =
      run_command("mosquitto_sub -p " + port +
                  " -t homeassistant/button/rotord-test/preset_1/config -C 1 -W 10")
          .out;
  EXPECT_NE(button.find(R"("command_topic":"rotord/test/cmd/preset")"), std::string::npos)
      << button;
  EXPECT_NE(button.find(R"("payload_press":"{\"name\":\"EU\"}")"), std::string::npos) << button;
  const std::string state =
      run_command("mosquitto_sub -p " + port + " -t rotord/test/state -C 1 -W 10").out;
  EXPECT_NE(state.find(R"("beam":{"az_deg":)"), std::string::npos) << state;
  // A new preset is announced at once.
  ASSERT_EQ(post("/api/presets", R"({"name": "JA", "az": 330})").status, 200);
  const std::string second =
      run_command("mosquitto_sub -p " + port +
                  " -t homeassistant/button/rotord-test/preset_2/config -C 1 -W 10")
          .out;
  EXPECT_NE(second.find(R"(Turn to JA (330)"), std::string::npos) << second;
  // Every discovery message, presets and the 16 wear and slip sensors
  // included, against the schema.
  const std::string file = dir + "/discovery.txt";
  ASSERT_EQ(
      run_command("mosquitto_sub -p " + port + " -t 'homeassistant/#' -v -C 25 -W 10 > " + file).rc,
      0);
  const CommandOutput check = run_command("python3 " ROTORD_SOURCE_DIR
                                          "/tests/interop/ha_discovery_check.py " ROTORD_SOURCE_DIR
                                          "/tests/data/mqtt/ha_discovery.schema.json " +
                                          file + " rotord/test");
  EXPECT_EQ(check.rc, 0) << check.out;
  EXPECT_NE(check.out.find("25 messages, 25 entities, 0 problems"), std::string::npos) << check.out;
}

}  // namespace
}  // namespace rotord::testing
