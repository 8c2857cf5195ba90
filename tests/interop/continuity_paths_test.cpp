// The continuity rule (docs/tracking.md, "Trackers through the protocols") on
// the paths the rotctld, GS-232 and WRC tests do not take, through the real
// daemon on the manual clock: a stream of 0..360 go-tos across north (340 ..
// 359, then 4 and 9) sent over REST (curl-like HTTP from one address), MQTT
// (mosquitto_rr through a real Mosquitto broker) and PstRotator's UDP
// messages ends on the turn continuous with it, 369 on the 450 deg G-5500,
// not back at 9 (the lead rule, docs/tracking.md "Fewer motor starts", sends
// the axis of such a steady stream up to 6 deg further: 369..375).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "mosquitto_broker.hpp"
#include "shell.hpp"
#include "udp_socket.hpp"

namespace rotord::testing {
namespace {

constexpr double kStream[] = {340.0, 345.0, 350.0, 355.0, 359.0, 4.0, 9.0};

/// Sends the stream with `send` (each go-to 1.5 s of controller time apart)
/// and returns where the azimuth is headed then (unwrapped, GET /api/status).
double stream_across_north(DaemonProcess& daemon, const std::function<void(double)>& send) {
  for (const double az : kStream) {
    send(az);
    EXPECT_GE(daemon.advance_ms(1500), 0);
  }
  const std::string s = http(daemon.ports().web, "GET", "/api/status").body;
  return json_number(s, "target_deg", s.find("\"az\""));
}

/// 9 on the turn continuous with the stream (369), led by at most 6 deg.
void expect_on_the_turn(double target_deg) {
  EXPECT_GE(target_deg, 368.5);
  EXPECT_LE(target_deg, 369.0 + 6.0);
}

TEST(ContinuityPaths, RestStreamAcrossNorthStaysOnItsTurn) {
  const std::string dir = make_temp_dir("rotord-continuity-rest");
  DaemonProcess daemon(
      {"--sim", "g5500", "--clock", "manual", "--config", dir + "/conf/settings.json"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const double target = stream_across_north(daemon, [&](double az) {
    char body[48];
    std::snprintf(body, sizeof body, "{\"az\":%.2f,\"el\":20}", az);
    const HttpResponse r = http(daemon.ports().web, "POST", "/api/goto", body);
    EXPECT_EQ(r.status, 200) << r.body;
  });
  std::printf("[ continuity ] REST stream 340 -> 9 across north: az target %.1f\n", target);
  expect_on_the_turn(target);
  run_command("rm -rf " + dir);
}

TEST(ContinuityPaths, MqttStreamAcrossNorthStaysOnItsTurn) {
  const std::string dir = make_temp_dir("rotord-continuity-mqtt");
  const int port = free_port();
  MosquittoBroker broker(dir, "127.0.0.1", port, "allow_anonymous true\n",
                         "-p " + std::to_string(port));
  std::ofstream(dir + "/rotord.json")
      << R"({"mqtt.enabled": true, "mqtt.host": "127.0.0.1", "mqtt.port": )" << port
      << R"(, "mqtt.prefix": "rotord/test", "mqtt.client_id": "rotord-test", )"
      << R"("mqtt.control": true})"
      << "\n";
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual", "--config", dir + "/rotord.json"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  ASSERT_TRUE(daemon.wait_for_output("mqtt: connected")) << daemon.output();
  const double target = stream_across_north(daemon, [&](double az) {
    char body[48];
    std::snprintf(body, sizeof body, "{\"az\":%.2f,\"el\":20}", az);
    // mosquitto_rr waits for the result: each go-to is obeyed before the next.
    const std::string r =
        run_command("mosquitto_rr -p " + std::to_string(port) +
                    " -t rotord/test/cmd/goto -e rotord/test/result -W 10 -m '" + body + "' 2>&1")
            .out;
    EXPECT_NE(r.find("\"status\":200"), std::string::npos) << r;
  });
  std::printf("[ continuity ] MQTT stream 340 -> 9 across north: az target %.1f\n", target);
  expect_on_the_turn(target);
  run_command("rm -rf " + dir);
}

TEST(ContinuityPaths, PstRotatorUdpStreamAcrossNorthStaysOnItsTurn) {
  const std::string dir = make_temp_dir("rotord-continuity-udp");
  // PstRotator answers at its port + 1: find a pair that is free.
  int pst_port = 0;
  std::unique_ptr<Udp> replies;
  for (int attempt = 0; attempt < 20 && !(replies && replies->bound()); ++attempt) {
    pst_port = Udp().port();
    replies = std::make_unique<Udp>(pst_port + 1);
  }
  ASSERT_TRUE(replies->bound());
  std::ofstream(dir + "/rotord.json")
      << R"({"pst.enabled": true, "pst.port": )" << pst_port << "}\n";
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual", "--config", dir + "/rotord.json"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  Udp client;
  const double target = stream_across_north(daemon, [&](double az) {
    char datagram[64];
    std::snprintf(datagram, sizeof datagram, "<PST><AZIMUTH>%.2f</AZIMUTH></PST>", az);
    client.send_to(pst_port, datagram);
    // The answer to a query sent after it says the go-to was read.
    client.send_to(pst_port, "<PST>AZ?</PST>");
    EXPECT_EQ(replies->receive().rfind("AZ:", 0), 0u);
  });
  std::printf("[ continuity ] PstRotator UDP stream 340 -> 9 across north: az target %.1f\n",
              target);
  expect_on_the_turn(target);
  run_command("rm -rf " + dir);
}

}  // namespace
}  // namespace rotord::testing
