// The HTTP session and REST API on a controller with fake hardware: every
// endpoint, its errors, the event stream, the assets and the timeouts.
#include <gtest/gtest.h>

#include <string>

#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "json/json_reader.hpp"
#include "memory_storage.hpp"
#include "web/assets.hpp"
#include "web/http_session.hpp"

namespace rotord::web {
namespace {

using rotord::testing::HttpResponse;
using rotord::testing::MemoryStorage;
using rotord::testing::parse_responses;
using rotord::testing::StringSink;
using settings::Id;

class CountingReboot final : public command::SystemHooks {
 public:
  int requests = 0;
  const char* reboot() override {
    ++requests;
    return nullptr;
  }
  const char* reboot_to_bootloader() override { return "not here"; }
};

class HttpApi : public ::testing::Test {
 protected:
  HttpApi() {
    defaults = r.settings;
    r.run_ms(50);
  }

  rotord::testing::FakeRotator r;
  settings::Settings defaults;
  MemoryStorage storage;
  CountingReboot reboot;
  Api api{ApiContext{*r.controller, &storage, &defaults, &reboot, "9.9.9"}};
  HttpSession session{api};

  std::vector<HttpResponse> send(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    return parse_responses(sink.data);
  }
  HttpResponse get(const std::string& path) {
    auto rs = send("GET " + path + " HTTP/1.1\r\nHost: localhost\r\n\r\n");
    return rs.empty() ? HttpResponse{} : rs[0];
  }
  HttpResponse post(const std::string& path, const std::string& body,
                    const std::string& type = "application/json") {
    auto rs = send(rotord::testing::post_request(path, body, type));
    return rs.empty() ? HttpResponse{} : rs[0];
  }
  static bool has(const HttpResponse& res, const std::string& text) {
    return res.body.find(text) != std::string::npos;
  }
  /// The port's loop for `ticks` ticks of 10 ms: the controller runs, then
  /// the session polls; it stops early once the session closes.
  void run_ticks(StringSink& sink, int ticks) {
    for (int tick = 0; tick < ticks && !session.wants_close(); ++tick) {
      r.run_ms(10);
      session.poll(r.now, sink);
    }
  }
  /// All a session sent before it closed a request that took too long: one
  /// 408 that says why.
  static void expect_one_408(const StringSink& sink, const char* why) {
    const auto rs = parse_responses(sink.data);
    ASSERT_EQ(rs.size(), 1u);
    EXPECT_EQ(rs[0].status, 408);
    EXPECT_NE(rs[0].body.find(why), std::string::npos);
  }
};

TEST_F(HttpApi, StatusIsJsonWithBothAxes) {
  const HttpResponse res = get("/api/status");
  EXPECT_EQ(res.status, 200);
  EXPECT_EQ(res.header("Content-Type"), "application/json");
  EXPECT_EQ(res.header("Connection"), "keep-alive");
  EXPECT_TRUE(JsonObjectReader(res.body).valid()) << res.body;
  EXPECT_TRUE(has(res, R"("version":"9.9.9")"));
  EXPECT_TRUE(has(res, R"("position_deg":100)")) << res.body;
  EXPECT_TRUE(has(res, R"("el":{"position_deg":20)")) << res.body;
  EXPECT_TRUE(has(res, R"("az_max":450)"));
  EXPECT_TRUE(has(res, R"("fault":"none")"));
  EXPECT_FALSE(session.wants_close());
}

TEST_F(HttpApi, GotoMovesAndReportsTheTarget) {
  HttpResponse res = post("/api/goto", R"({"az": 200, "el": 45})");
  EXPECT_EQ(res.status, 200) << res.body;
  EXPECT_EQ(res.body, R"({"ok":true,"az_target":200,"el_target":45})");
  EXPECT_FLOAT_EQ(r.controller->status().az.target_deg, 200.0f);
  EXPECT_FLOAT_EQ(r.controller->status().el.target_deg, 45.0f);
  res = post("/api/goto", R"({"az": 20, "unwrapped": true})");
  EXPECT_EQ(res.status, 200) << res.body;
  EXPECT_FLOAT_EQ(r.controller->status().az.target_deg, 20.0f);
}

TEST_F(HttpApi, GotoErrors) {
  const float before = r.controller->status().az.target_deg;
  EXPECT_EQ(post("/api/goto", R"({"az": 500})").status, 422);
  EXPECT_TRUE(has(post("/api/goto", R"({"az": 500})"), "outside the travel 0..450"));
  EXPECT_EQ(post("/api/goto", R"({"el": 181})").status, 422);
  EXPECT_EQ(post("/api/goto", R"({"az": "north"})").status, 400);
  EXPECT_TRUE(has(post("/api/goto", R"({"az": "north"})"), "az must be a number"));
  EXPECT_EQ(post("/api/goto", R"({"azz": 1})").status, 400);
  EXPECT_EQ(post("/api/goto", R"({})").status, 400);
  EXPECT_EQ(post("/api/goto", "").status, 400);
  EXPECT_EQ(post("/api/goto", R"({"az": 1,})").status, 400);
  EXPECT_TRUE(has(post("/api/goto", "{\"az\": 1,}"), "invalid JSON"));
  EXPECT_EQ(post("/api/goto", R"({"az": 10})", "text/plain").status, 415);
  EXPECT_EQ(post("/api/goto", R"({"az": 10})", "application/x-www-form-urlencoded").status, 415);
  EXPECT_FALSE(r.controller->status().az.has_target);
  EXPECT_FLOAT_EQ(r.controller->status().az.target_deg, before);
}

TEST_F(HttpApi, GotoOnAnAzimuthOnlyRotatorRefusesElevation) {
  rotord::testing::FakeRotator az_only(false);
  Api api2{ApiContext{*az_only.controller, nullptr, nullptr, nullptr, "x"}};
  HttpSession s2{api2};
  StringSink sink;
  const std::string body = R"({"az":90,"el":10})";
  s2.receive(rotord::testing::post_request("/api/goto", body), sink);
  const auto rs = parse_responses(sink.data);
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 422);
  EXPECT_NE(rs[0].body.find("no elevation axis"), std::string::npos);
  EXPECT_FALSE(az_only.controller->status().az.has_target);
}

TEST_F(HttpApi, MoveHoldsOnlyWhileRenewedOnTheTransportClock) {
  // The transport's clock and controller time differ (--speedup, --clock
  // manual): hold_ms is the client's time, and the port's loop (api.poll)
  // stops the jog even with no connection left.
  Millis wall_ms = 1000;
  api.poll(wall_ms);
  HttpResponse res = post("/api/move", R"({"dir":"cw","hold_ms":300,"speed":50})");
  ASSERT_EQ(res.status, 200) << res.body;
  r.run_ms(100);
  api.poll(wall_ms += 100);
  EXPECT_TRUE(r.controller->status().az.jogging);
  EXPECT_TRUE(r.az.drive.cw());
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","hold_ms":300})").status, 200);  // renewal
  r.run_ms(100);
  api.poll(wall_ms += 250);
  EXPECT_TRUE(r.controller->status().az.jogging);
  r.run_ms(50);
  api.poll(wall_ms += 100);  // 350 ms of the client's time without a renewal
  EXPECT_FALSE(r.controller->status().az.jogging);
  r.run_ms(2000);
  EXPECT_FALSE(r.az.drive.cw());
}

TEST_F(HttpApi, MoveStopAndElevation) {
  ASSERT_EQ(post("/api/move", R"({"dir":"up"})").status, 200);
  r.run_ms(100);
  EXPECT_TRUE(r.controller->status().el.jogging);
  ASSERT_EQ(post("/api/move", R"({"axis":"el","dir":"stop"})").status, 200);
  EXPECT_FALSE(r.controller->status().el.jogging);
  ASSERT_EQ(post("/api/move", R"({"axis":"az","dir":"ccw","hold_ms":0})").status, 200);
  EXPECT_TRUE(r.controller->status().az.jogging);
  ASSERT_EQ(post("/api/move", R"({"dir":"stop"})").status, 200);
  EXPECT_FALSE(r.controller->status().az.jogging);
}

TEST_F(HttpApi, MoveErrors) {
  EXPECT_EQ(post("/api/move", R"({})").status, 400);
  EXPECT_EQ(post("/api/move", R"({"dir":5})").status, 400);
  EXPECT_EQ(post("/api/move", R"({"dir":"left"})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","axis":"x"})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"up","axis":"az"})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","speed":0})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","speed":50.5})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","hold_ms":50})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","hold_ms":20000})").status, 422);
  EXPECT_EQ(post("/api/move", R"({"dir":"cw","hold_ms":"1"})").status, 400);
  EXPECT_FALSE(r.controller->status().az.jogging);
  EXPECT_FALSE(r.controller->status().el.jogging);
}

TEST_F(HttpApi, StopWorksWithoutAJsonContentType) {
  ASSERT_EQ(post("/api/goto", R"({"az":300})").status, 200);
  const auto rs = send("POST /api/stop HTTP/1.1\r\n\r\n");
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 200);
  EXPECT_FALSE(r.controller->status().az.has_target);
}

TEST_F(HttpApi, ParkModeSpeedReset) {
  r.settings.set(Id::kParkAzDeg, 180);
  EXPECT_EQ(post("/api/park", "").status, 200);
  EXPECT_EQ(r.controller->status().mode, Mode::kPark);
  EXPECT_FLOAT_EQ(r.controller->status().az.target_deg, 180.0f);
  EXPECT_EQ(post("/api/mode", R"({"mode":"idle"})").status, 200);
  EXPECT_EQ(r.controller->status().mode, Mode::kIdle);
  EXPECT_EQ(post("/api/mode", R"({"mode":"park"})").status, 200);
  EXPECT_EQ(r.controller->status().mode, Mode::kPark);
  EXPECT_EQ(post("/api/mode", R"({"mode":"goto"})").status, 422);
  EXPECT_EQ(post("/api/mode", R"({"mode":"dance"})").status, 422);
  EXPECT_EQ(post("/api/mode", R"({})").status, 400);
  EXPECT_EQ(post("/api/speed", R"({"speed_pct":40})").status, 200);
  EXPECT_EQ(r.controller->status().speed_pct, 40);
  EXPECT_EQ(post("/api/speed", R"({"speed_pct":101})").status, 422);
  EXPECT_EQ(post("/api/speed", R"({"speed_pct":true})").status, 400);
  EXPECT_EQ(r.controller->status().speed_pct, 40);
  EXPECT_EQ(post("/api/reset", "{}").status, 200);
  EXPECT_EQ(r.controller->status().speed_pct, 100);
}

TEST_F(HttpApi, AFaultIsReportedAndRefusesMotionUntilReset) {
  r.az.adc.counts = 0;  // the wiper at the rail: a sensor fault
  r.run_ms(500);
  ASSERT_NE(r.controller->status().az.fault, AxisFault::kNone);
  EXPECT_TRUE(has(get("/api/status"), R"("fault":true)"));
  HttpResponse res = post("/api/goto", R"({"az":200})");
  EXPECT_EQ(res.status, 409);
  EXPECT_TRUE(has(res, "POST /api/reset"));
  r.az.set_deg(100);
  EXPECT_EQ(post("/api/reset", "").status, 200);
  r.run_ms(100);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kNone);
  EXPECT_EQ(post("/api/goto", R"({"az":200})").status, 200);
}

TEST_F(HttpApi, SettingsGetAndPartialPost) {
  HttpResponse res = get("/api/settings");
  EXPECT_EQ(res.status, 200);
  EXPECT_TRUE(has(res, R"("az.max_deg":450)"));
  EXPECT_TRUE(has(res, R"("az.drive":"relay")"));
  EXPECT_TRUE(has(res, R"("el.enabled":true)"));
  res = post("/api/settings", R"({"az.offset_deg": 2.5, "az.drive": "hbridge"})");
  EXPECT_EQ(res.status, 200) << res.body;
  EXPECT_EQ(res.body, R"({"ok":true,"saved":true,"changed":["az.offset_deg","az.drive"],)"
                      R"("restart_required":["az.drive"]})");
  EXPECT_DOUBLE_EQ(r.settings.get(Id::kAzOffsetDeg), 2.5);
  EXPECT_EQ(storage.saves, 1);
  EXPECT_NE(storage.document.find("\"az.offset_deg\": 2.5"), std::string::npos);
  // Unchanged values: nothing to save.
  EXPECT_EQ(post("/api/settings", R"({"az.offset_deg": 2.5})").status, 200);
  EXPECT_EQ(storage.saves, 1);
}

TEST_F(HttpApi, InvalidSettingsChangeNothingAndSaveNothing) {
  const settings::Settings before = r.settings;
  HttpResponse res =
      post("/api/settings", R"({"az.offset_deg": 3, "az.max_deg": 9999, "az.drive": "steam",)"
                            R"( "el.enabled": 1, "no.such": 1})");
  EXPECT_EQ(res.status, 422);
  EXPECT_TRUE(has(res, R"("az.max_deg":"outside the allowed range")")) << res.body;
  EXPECT_TRUE(has(res, R"("az.drive":"not one of the choices")"));
  EXPECT_TRUE(has(res, R"("el.enabled":"expected true or false")"));
  EXPECT_TRUE(has(res, R"("no.such":"unknown setting")"));
  EXPECT_FALSE(has(res, R"("az.offset_deg")"));
  EXPECT_EQ(r.settings.get(Id::kAzOffsetDeg), before.get(Id::kAzOffsetDeg));
  EXPECT_EQ(storage.saves, 0);
  // A rule across settings names the fields it involves.
  res = post("/api/settings", R"({"az.min_deg": 100, "az.max_deg": 50})");
  EXPECT_EQ(res.status, 422);
  EXPECT_TRUE(has(res, R"("error":"az.min_deg must be below az.max_deg")")) << res.body;
  EXPECT_TRUE(has(res, R"("az.min_deg":"az.min_deg must be below az.max_deg")"));
  EXPECT_TRUE(has(res, R"("az.max_deg":"az.min_deg must be below az.max_deg")"));
  EXPECT_EQ(r.settings.get(Id::kAzMinDeg), before.get(Id::kAzMinDeg));
  EXPECT_EQ(post("/api/settings", "{\"az.min_deg\": ").status, 400);
  EXPECT_EQ(post("/api/settings", "[]").status, 400);
  EXPECT_EQ(storage.saves, 0);
}

TEST_F(HttpApi, AFailedSaveRollsBack) {
  storage.fail = true;
  const HttpResponse res = post("/api/settings", R"({"az.offset_deg": 7})");
  EXPECT_EQ(res.status, 500);
  EXPECT_TRUE(has(res, "nothing was changed"));
  EXPECT_EQ(r.settings.get(Id::kAzOffsetDeg), 0.0);
}

TEST_F(HttpApi, ResetRestoresThePortDefaults) {
  ASSERT_EQ(post("/api/settings", R"({"az.offset_deg": 7, "park.az_deg": 90})").status, 200);
  const HttpResponse res = post("/api/settings/reset", "");
  EXPECT_EQ(res.status, 200) << res.body;
  EXPECT_TRUE(has(res, R"("changed":["park.az_deg","az.offset_deg"])")) << res.body;
  EXPECT_EQ(r.settings.get(Id::kAzOffsetDeg), 0.0);
  // The port's defaults (here: the fake's calibration), not the bare table.
  EXPECT_EQ(r.settings.get(Id::kAzPotCalLoCounts), 100.0);
  EXPECT_EQ(storage.saves, 2);
}

TEST_F(HttpApi, SchemaComesFromTheTable) {
  const HttpResponse res = get("/api/settings/schema");
  EXPECT_EQ(res.status, 200);
  EXPECT_TRUE(JsonObjectReader(res.body).valid());
  // The groups as an owner thinks of them, in the form's order.
  EXPECT_TRUE(has(res, R"("groups":["Rotator","Wiring","Calibration","Limits and safety",)"
                       R"("Station","Tracking","Network","Access","Integrations"])"))
      << res.body;
  EXPECT_TRUE(has(res, R"({"key":"az.drive","type":"enum","unit":"","min":0,"max":3,)"
                       R"("default":"relay","group":"Rotator","label":"Drive type","choices":)"));
  // A row's condition and whether it is rarely changed; the help is the web
  // UI's asset (settings_help.js), not in the schema.
  EXPECT_TRUE(has(res, R"("label":"Slow zone before the target",)"
                       R"("when":"az.drive=relay_two_speed|relay_voltage_select|hbridge",)"));
  EXPECT_FALSE(has(res, R"("help":)"));
  EXPECT_TRUE(has(res, R"("label":"Relay rest time",)")) << res.body;
  EXPECT_TRUE(has(res, R"(,"advanced":true,"choices":[],"restart":false})"));
  // This test's Api names no platform: the schema then names none either.
  EXPECT_FALSE(has(res, R"("platform":)"));
  EXPECT_TRUE(has(res, R"("choices":["relay","relay_two_speed","relay_voltage_select","hbridge"],)"
                       R"("restart":true})"));
  // The default reported is the port's (the fake sets 100 counts).
  EXPECT_TRUE(has(res, R"({"key":"az.pot_cal_lo_counts","type":"float","unit":"counts","min":0,)"
                       R"("max":65535,"default":100,)"));
  std::size_t rows = 0;
  for (std::size_t pos = res.body.find("\"key\":"); pos != std::string::npos;
       pos = res.body.find("\"key\":", pos + 1))
    ++rows;
  EXPECT_EQ(rows, settings::kCount);
}

TEST_F(HttpApi, RebootIsHandedToThePortAndClosesTheConnection) {
  const HttpResponse res = post("/api/reboot", "{}");
  EXPECT_EQ(res.status, 202);
  EXPECT_EQ(res.header("Connection"), "close");
  EXPECT_EQ(reboot.requests, 1);
  EXPECT_TRUE(session.wants_close());
}

TEST_F(HttpApi, RebootWithoutAPortHookIs501) {
  Api plain{ApiContext{*r.controller, nullptr, nullptr, nullptr, "x"}};
  HttpSession s{plain};
  StringSink sink;
  s.receive("POST /api/reboot HTTP/1.1\r\nContent-Type: application/json\r\n\r\n", sink);
  EXPECT_EQ(parse_responses(sink.data).at(0).status, 501);
}

TEST_F(HttpApi, UnknownPathsAndMethods) {
  HttpResponse res = get("/api/nope");
  EXPECT_EQ(res.status, 404);
  EXPECT_EQ(res.body, R"({"error":"no such API endpoint"})");
  res = get("/api/goto");
  EXPECT_EQ(res.status, 405);
  EXPECT_EQ(res.header("Allow"), "POST");
  res = send("DELETE /api/status HTTP/1.1\r\n\r\n").at(0);
  EXPECT_EQ(res.status, 405);
  EXPECT_EQ(res.header("Allow"), "GET, HEAD");
  EXPECT_EQ(send("PUT /api/settings HTTP/1.1\r\n\r\n").at(0).header("Allow"), "GET, HEAD, POST");
  EXPECT_EQ(get("/nothing.html").status, 404);
  EXPECT_EQ(send("POST /index.html HTTP/1.1\r\n\r\n").at(0).status, 405);
  EXPECT_FALSE(session.wants_close());  // all of these keep the connection
}

TEST_F(HttpApi, FramingErrorsAnswerAndClose) {
  const auto rs = send("POST /api/settings HTTP/1.1\r\nContent-Length: 100000\r\n\r\n");
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 413);
  EXPECT_EQ(rs[0].header("Connection"), "close");
  EXPECT_TRUE(has(rs[0], "too large"));
  EXPECT_TRUE(session.wants_close());
  EXPECT_TRUE(send("GET /api/status HTTP/1.1\r\n\r\n").empty());  // nothing after the close
}

TEST_F(HttpApi, KeepAliveAndPipelining) {
  const auto rs = send(
      "GET /api/status HTTP/1.1\r\n\r\n"
      "POST /api/goto HTTP/1.1\r\nContent-Type: application/json\r\nContent-Length: 10\r\n\r\n"
      "{\"az\":150}"
      "GET /api/settings HTTP/1.1\r\nConnection: close\r\n\r\n");
  ASSERT_EQ(rs.size(), 3u);
  EXPECT_EQ(rs[0].status, 200);
  EXPECT_EQ(rs[1].status, 200);
  EXPECT_EQ(rs[2].status, 200);
  EXPECT_EQ(rs[2].header("Connection"), "close");
  EXPECT_TRUE(session.wants_close());
  EXPECT_FLOAT_EQ(r.controller->status().az.target_deg, 150.0f);
}

TEST_F(HttpApi, AssetsAreServedGzippedWithAnETag) {
  HttpResponse res = get("/");
  ASSERT_EQ(res.status, 200);
  EXPECT_EQ(res.header("Content-Encoding"), "gzip");
  EXPECT_EQ(res.header("Content-Type"), "text/html; charset=utf-8");
  ASSERT_GE(res.body.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(res.body[0]), 0x1f);  // gzip magic
  EXPECT_EQ(static_cast<unsigned char>(res.body[1]), 0x8b);
  const std::string etag = res.header("ETag");
  ASSERT_FALSE(etag.empty());
  const auto rs = send("GET /index.html HTTP/1.1\r\nIf-None-Match: " + etag + "\r\n\r\n");
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 304);
  EXPECT_TRUE(rs[0].body.empty());
  for (const char* path :
       {"/style.css", "/common.js", "/control.js", "/settings.html", "/settings.js"})
    EXPECT_NE(find_asset(path), nullptr) << path;
  res = send("HEAD /style.css HTTP/1.1\r\n\r\n").at(0);
  EXPECT_EQ(res.status, 200);
  EXPECT_EQ(res.header("Content-Length"), std::to_string(find_asset("/style.css")->gzip_size));
}

TEST_F(HttpApi, EventStreamPushesTenPerSecondWhileMovingAndOneWhenIdle) {
  StringSink sink;
  session.receive("GET /api/events HTTP/1.1\r\nAccept: text/event-stream\r\n\r\n", sink);
  EXPECT_TRUE(session.streaming_events());
  EXPECT_EQ(sink.data.rfind("HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\n", 0), 0u);
  EXPECT_EQ(sink.data.find("Content-Length"), std::string::npos);
  auto events = [&] {
    std::size_t n = 0;
    for (std::size_t pos = sink.data.find("data: {"); pos != std::string::npos;
         pos = sink.data.find("data: {", pos + 1))
      ++n;
    return n;
  };
  EXPECT_EQ(events(), 1u);  // the current state at once
  auto run = [&](Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      r.run_ms(10);
      session.poll(r.now, sink);
    }
  };
  run(3000);
  EXPECT_LE(events(), 5u);  // idle: about one a second
  r.controller->move(AxisId::kAz, Direction::kCw);
  const std::size_t before = events();
  run(1000);
  EXPECT_GE(events() - before, 9u);  // moving: 10 per second
  // Bytes from the client are ignored; the stream goes on.
  session.receive("GET /api/status HTTP/1.1\r\n\r\n", sink);
  EXPECT_EQ(sink.data.find("HTTP/1.1", 10), std::string::npos);
  EXPECT_FALSE(session.wants_close());
}

TEST_F(HttpApi, SlowAndIdleClientsAreDropped) {
  // A transport polls its sessions every tick: the bytes are stamped then.
  StringSink sink;
  session.receive("GET /api/sta", sink);
  session.poll(r.now, sink);
  r.run_ms(HttpSession::kRequestDeadlineMs + 100);
  session.poll(r.now, sink);
  const auto rs = parse_responses(sink.data);
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 408);
  EXPECT_TRUE(session.wants_close());

  HttpSession idle{api};
  StringSink sink2;
  idle.receive("GET /api/status HTTP/1.1\r\n\r\n", sink2);
  idle.poll(r.now, sink2);
  r.run_ms(HttpSession::kIdleTimeoutMs / 2);
  idle.poll(r.now, sink2);
  EXPECT_FALSE(idle.wants_close());
  r.run_ms(HttpSession::kIdleTimeoutMs);
  idle.poll(r.now, sink2);
  EXPECT_TRUE(idle.wants_close());
}

TEST_F(HttpApi, ATricklingRequestGets408AtItsDeadlineWhateverItKeepsSending) {
  // Issue 12: one header byte every 2 s used to restart a 10 s timeout for
  // ever. The deadline runs from the first byte.
  StringSink sink;
  const std::string head = "GET /api/status HTTP/1.1\r\nX-Slow: " + std::string(200, 'a');
  const Millis start = r.now;
  std::size_t sent = 0;
  while (!session.wants_close() && sent < head.size()) {
    session.receive(head.substr(sent++, 1), sink);
    run_ticks(sink, 200);
  }
  ASSERT_TRUE(session.wants_close());
  EXPECT_LE(r.now - start, HttpSession::kRequestDeadlineMs + 2000);
  expect_one_408(sink, "not completed in time");
}

TEST_F(HttpApi, ABodyArrivingTooSlowlyGets408BeforeTheDeadline) {
  StringSink sink;
  session.receive(
      "POST /api/settings HTTP/1.1\r\nContent-Type: application/json\r\n"
      "Content-Length: 4000\r\n\r\n{",
      sink);
  const Millis start = r.now;
  for (int second = 0; second < 10 && !session.wants_close(); ++second) {
    run_ticks(sink, 100);
    session.receive(" ", sink);  // a byte a second
  }
  ASSERT_TRUE(session.wants_close());
  EXPECT_LT(r.now - start, HttpSession::kRequestDeadlineMs);
  expect_one_408(sink, "too slowly");
}

TEST_F(HttpApi, ABodyAtAnOrdinaryPaceIsServed) {
  // 2 KB in 100-byte pieces every 100 ms (1 KB/s): slow, but well within the rate.
  StringSink sink;
  const std::string body = "{\"park.az_deg\": 12" + std::string(2000, ' ') + "}";
  session.receive(
      "POST /api/settings HTTP/1.1\r\nContent-Type: application/json\r\n"
      "Content-Length: " +
          std::to_string(body.size()) + "\r\n\r\n",
      sink);
  for (std::size_t sent = 0; sent < body.size(); sent += 100) {
    run_ticks(sink, 10);
    session.receive(body.substr(sent, 100), sink);
  }
  const auto rs = parse_responses(sink.data);
  ASSERT_EQ(rs.size(), 1u) << sink.data;
  EXPECT_EQ(rs[0].status, 200) << rs[0].body;
}

TEST_F(HttpApi, StrayLineEndsDoNotKeepAnIdleConnectionOpen) {
  StringSink sink;
  session.poll(r.now, sink);
  for (int n = 0; n < 20 && !session.wants_close(); ++n) {
    session.receive("\r\n", sink);
    run_ticks(sink, 100);
  }
  EXPECT_TRUE(session.wants_close());
}

TEST_F(HttpApi, AnEventStreamSaysSoToItsTransport) {
  StringSink sink;
  EXPECT_FALSE(session.is_event_stream());
  session.receive("GET /api/status HTTP/1.1\r\n\r\n", sink);
  EXPECT_FALSE(session.is_event_stream());
  session.receive("GET /api/events HTTP/1.1\r\n\r\n", sink);
  EXPECT_TRUE(session.is_event_stream());
}

TEST_F(HttpApi, TimeoutsRunOnTheTransportsClockNotOnControllerTime) {
  // rotord --speedup 20: a minute of rotator time in three seconds of wall
  // time, which is what the transport polls with. No timeout yet.
  StringSink sink;
  HttpSession idle{api};
  idle.poll(0, sink);
  idle.receive("GET /api/status HTTP/1.1\r\n\r\n", sink);
  idle.poll(10, sink);
  session.receive("GET /api/sta", sink);
  session.poll(10, sink);
  for (Millis wall = 20; wall <= 3000; wall += 10) {
    r.run_ms(200);
    idle.poll(wall, sink);
    session.poll(wall, sink);
  }
  EXPECT_FALSE(idle.wants_close());
  EXPECT_FALSE(session.wants_close());
  idle.poll(10 + HttpSession::kIdleTimeoutMs + 10, sink);
  EXPECT_TRUE(idle.wants_close());
  session.poll(10 + HttpSession::kRequestDeadlineMs + 10, sink);
  EXPECT_TRUE(session.wants_close());
}

TEST(HttpSessionLimits, TooManyConnectionsReplyIsAValidResponse) {
  const auto rs = parse_responses(std::string(HttpSession::kTooManyConnections));
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 503);
  EXPECT_EQ(rs[0].body, R"({"error":"too many connections"})");
}

}  // namespace
}  // namespace rotord::web

namespace rotord::web {
namespace {

/// A transport with a bounded buffer, as the Pico's lwIP connection is
/// (about 12.7 KB: lwIP's send buffer and the 1 KiB output buffer): it says
/// how much it takes now, and a write beyond that would drop the client.
struct BoundedSink final : protocol::ByteSink {
  std::string data;
  std::size_t free = 0;
  bool overflowed = false;
  void write(std::string_view bytes) override {
    if (bytes.size() > free) overflowed = true;
    data.append(bytes);
    free -= std::min(free, bytes.size());
  }
  std::size_t room() const override { return free; }
};

TEST_F(HttpApi, AResponseLongerThanTheTransportTakesGoesOutInWindows) {
  const std::string request = "GET /api/settings/schema HTTP/1.1\r\nHost: localhost\r\n\r\n";
  StringSink whole;
  HttpSession reference(api);
  reference.receive(request, whole);
  ASSERT_GT(whole.data.size(), 3 * 12700u);  // the schema: more than three windows

  BoundedSink sink;
  sink.free = 12700;
  session.receive(request, sink);
  ASSERT_TRUE(session.output_pending());
  EXPECT_FALSE(session.between_requests());
  int windows = 1;
  while (session.output_pending() && windows < 100) {
    session.poll(r.now, sink);  // nothing goes out from poll meanwhile
    sink.free = 12700;          // the peer acknowledged everything
    session.write_more(static_cast<std::size_t>(-1), sink);
    ++windows;
  }
  EXPECT_FALSE(sink.overflowed);
  EXPECT_EQ(sink.data, whole.data);
  EXPECT_GE(windows, 4);
  EXPECT_FALSE(session.wants_close());
  EXPECT_TRUE(session.between_requests());
  // The connection goes on: the next request is answered as usual.
  EXPECT_EQ(get("/api/status").status, 200);
}

TEST_F(HttpApi, AWindowedResponseThatChangesMeanwhileClosesTheConnection) {
  BoundedSink sink;
  sink.free = 2000;
  session.receive("GET /api/settings HTTP/1.1\r\nHost: localhost\r\n\r\n", sink);
  ASSERT_TRUE(session.output_pending());
  r.settings.set(settings::Id::kAzMinDeg, 5);  // the first window said 0
  sink.free = 100000;
  session.write_more(static_cast<std::size_t>(-1), sink);
  EXPECT_FALSE(session.output_pending());
  EXPECT_TRUE(session.wants_close());  // the client sees a short body and asks again
  EXPECT_EQ(sink.data.size(), 2000u);
}

TEST_F(HttpApi, ARequestPipelinedBehindAWindowedResponseClosesAfterIt) {
  BoundedSink sink;
  sink.free = 12700;
  session.receive("GET /api/settings/schema HTTP/1.1\r\nHost: localhost\r\n\r\n", sink);
  ASSERT_TRUE(session.output_pending());
  session.receive("GET /api/status HTTP/1.1\r\nHost: localhost\r\n\r\n", sink);
  while (session.output_pending()) {
    sink.free = 12700;
    session.write_more(static_cast<std::size_t>(-1), sink);
  }
  EXPECT_TRUE(session.wants_close());
  const std::vector<HttpResponse> responses = parse_responses(sink.data);
  ASSERT_EQ(responses.size(), 1u);
  EXPECT_EQ(responses[0].body.size(),
            std::strtoul(responses[0].header("Content-Length").c_str(), nullptr, 10));
}

}  // namespace
}  // namespace rotord::web
