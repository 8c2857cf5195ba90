// GET /metrics and GET /healthz (issue 12): the Prometheus text formatter,
// what counts as an error reply per protocol, the fault counters, and both
// pages through the HTTP session on fake hardware with a clock the test owns.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "loop/tick_scheduler.hpp"
#include "memory_storage.hpp"
#include "metrics/prometheus_writer.hpp"
#include "metrics/registry.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "storage/settings_saver.hpp"
#include "string_sink.hpp"
#include "web/http_session.hpp"

namespace rotord::metrics {
namespace {

using rotord::testing::StringSink;

/// The line protocols' counters (metrics::Protocol names HTTP only; the
/// others follow the registry's rows).
namespace line {
constexpr Protocol kWrc = line_metric(protocol::Personality::kWrc);
constexpr Protocol kRotctld = line_metric(protocol::Personality::kRotctld);
constexpr Protocol kGs232 = line_metric(protocol::Personality::kGs232);
constexpr Protocol kEasycomm = line_metric(protocol::Personality::kEasycomm);
constexpr Protocol kSeed = line_metric(protocol::Personality::kSeed);
}  // namespace line

std::string written(const std::function<void(PrometheusWriter&)>& body) {
  StringSink sink;
  {
    PrometheusWriter w(sink);
    body(w);
  }
  return sink.data;
}

TEST(PrometheusWriter, WritesHelpTypeAndLabelledSamples) {
  const std::string text = written([](PrometheusWriter& w) {
    w.family("rotord_axis_position_degrees", "gauge", "Position, degrees.");
    w.value({{"axis", "az"}}, 123.5);
    w.value({{"axis", "el"}}, -0.0);
    w.family("rotord_ticks_total", "counter", "Ticks.");
    w.integer({}, 18446744073709551615ull);
  });
  EXPECT_EQ(text,
            "# HELP rotord_axis_position_degrees Position, degrees.\n"
            "# TYPE rotord_axis_position_degrees gauge\n"
            "rotord_axis_position_degrees{axis=\"az\"} 123.5\n"
            "rotord_axis_position_degrees{axis=\"el\"} 0\n"
            "# HELP rotord_ticks_total Ticks.\n"
            "# TYPE rotord_ticks_total counter\n"
            "rotord_ticks_total 18446744073709551615\n");
}

TEST(PrometheusWriter, EscapesHelpAndLabelValuesAndSpellsNonFiniteNumbers) {
  const std::string text = written([](PrometheusWriter& w) {
    w.family("m", "gauge", "a \\ b\nc \"quoted\"");
    w.value({{"l", "x\"y\\z\nw"}, {"k", "v"}}, NAN);
    w.value({}, INFINITY);
    w.value({}, -INFINITY);
  });
  EXPECT_EQ(text,
            "# HELP m a \\\\ b\\nc \"quoted\"\n"
            "# TYPE m gauge\n"
            "m{l=\"x\\\"y\\\\z\\nw\",k=\"v\"} NaN\n"
            "m +Inf\n"
            "m -Inf\n");
}

TEST(PrometheusWriter, HelpLinesCanBeLeftOut) {
  StringSink sink;
  {
    PrometheusWriter w(sink, false);
    w.family("m_total", "counter", "h");
    w.integer({}, 3);
  }
  EXPECT_EQ(sink.data, "# TYPE m_total counter\nm_total 3\n");
}

TEST(PrometheusWriter, ALongLineCrossesTheBufferIntact) {
  const std::string long_value(1000, 'v');
  StringSink sink;
  {
    PrometheusWriter w(sink);
    w.family("m", "gauge", "h");
    w.integer({{"l", long_value}}, 7);
  }
  EXPECT_GT(sink.writes, 1);  // streamed, not held whole
  EXPECT_EQ(sink.data, "# HELP m h\n# TYPE m gauge\nm{l=\"" + long_value + "\"} 7\n");
}

TEST(PrometheusWriter, HistogramsAreCumulativeInSeconds) {
  static constexpr std::int64_t kBounds[] = {50, 1000, 2'500'000};
  Histogram h(kBounds);
  for (std::int64_t v : {10, 40, 600, 3'000'000}) h.add(v);
  const std::string text =
      written([&](PrometheusWriter& w) { w.histogram_seconds("rotord_x_seconds", "X.", h); });
  EXPECT_EQ(text,
            "# HELP rotord_x_seconds X.\n"
            "# TYPE rotord_x_seconds histogram\n"
            "rotord_x_seconds_bucket{le=\"0.00005\"} 2\n"
            "rotord_x_seconds_bucket{le=\"0.001\"} 3\n"
            "rotord_x_seconds_bucket{le=\"2.5\"} 3\n"
            "rotord_x_seconds_bucket{le=\"+Inf\"} 4\n"
            "rotord_x_seconds_sum 3.00065\n"
            "rotord_x_seconds_count 4\n");
}

TEST(PrometheusWriter, SecondsFromMicrosecondsAreExact) {
  char buf[32];
  auto text = [&](std::int64_t us) {
    return std::string(buf, PrometheusWriter::format_seconds(us, buf, sizeof buf));
  };
  EXPECT_EQ(text(0), "0");
  EXPECT_EQ(text(10'000), "0.01");
  EXPECT_EQ(text(1), "0.000001");
  EXPECT_EQ(text(12'345'678), "12.345678");
  EXPECT_EQ(text(-500'000), "-0.5");
  EXPECT_EQ(PrometheusWriter::format_seconds(12'345'678, buf, 3), 0u);  // does not fit
}

TEST(ErrorReplies, EachProtocolsErrorIsRecognisedAndNothingElse) {
  EXPECT_TRUE(is_error_reply(line::kWrc, "ERROR INVALID AZIMUTH\r\n"));
  EXPECT_FALSE(is_error_reply(line::kWrc, "OK AZ 100.0\r\n"));
  EXPECT_FALSE(is_error_reply(line::kWrc, "STATE AZ=1.0 SPEED=50 FLAGS=\r\n"));
  EXPECT_TRUE(is_error_reply(line::kRotctld, "RPRT -1\n"));
  EXPECT_TRUE(is_error_reply(line::kRotctld, "set_pos: 1 2\nRPRT -9\n"));
  EXPECT_FALSE(is_error_reply(line::kRotctld, "RPRT 0\n"));
  EXPECT_FALSE(is_error_reply(line::kRotctld, "100.000000\n20.000000\n"));
  EXPECT_TRUE(is_error_reply(line::kGs232, protocol::Gs232Session::kError));
  EXPECT_FALSE(is_error_reply(line::kGs232, "AZ=100\r\n"));
  EXPECT_TRUE(is_error_reply(line::kEasycomm, "ALRANGE\n"));
  EXPECT_FALSE(is_error_reply(line::kEasycomm, "AZ100.0 EL20.0\n"));
  EXPECT_TRUE(is_error_reply(line::kSeed, "$ERR,RANGE\r\n"));
  EXPECT_FALSE(is_error_reply(line::kSeed, "$OK,S,50\r\n"));
  EXPECT_TRUE(is_error_reply(Protocol::kHttp, "HTTP/1.1 404 Not Found\r\n"));
  EXPECT_TRUE(is_error_reply(Protocol::kHttp, "HTTP/1.1 503 Service Unavailable\r\n"));
  EXPECT_FALSE(is_error_reply(Protocol::kHttp, "HTTP/1.1 200 OK\r\n"));
  EXPECT_FALSE(is_error_reply(Protocol::kHttp, "{\"error\":\"x\"}"));  // a body, not a head
}

TEST(ErrorReplies, TheSessionsOwnErrorsAreCountedWhenSentThroughTheRegistry) {
  // What a transport does with every reply unit: the real sessions' errors.
  rotord::testing::FakeRotator r;
  Registry registry;
  struct Counting final : protocol::ByteSink {
    Registry& reg;
    Protocol p;
    Counting(Registry& registry_, Protocol protocol) : reg(registry_), p(protocol) {}
    void write(std::string_view bytes) override { reg.on_reply(p, bytes); }
  };
  protocol::WrcSession wrc(*r.controller, "9");
  protocol::RotctldSession rotctld(*r.controller, "9");
  protocol::Gs232Session gs232(*r.controller);
  protocol::EasycommSession easycomm(*r.controller, "9");
  protocol::SeedSession seed(*r.controller);
  Counting to_wrc(registry, line::kWrc), to_rotctld(registry, line::kRotctld),
      to_gs232(registry, line::kGs232), to_easycomm(registry, line::kEasycomm),
      to_seed(registry, line::kSeed);
  wrc.receive("AZ 9999\nAZ?\nBOGUS\n", to_wrc);
  rotctld.receive("P 9999 0\np\n\\no_such_command\n", to_rotctld);
  gs232.receive("M999\rC\rM\r", to_gs232);
  easycomm.receive("AZ999.0\nAZ\n", to_easycomm);
  seed.receive("$bogus\r\n$Q\r\n", to_seed);
  EXPECT_EQ(registry.protocol(line::kWrc).errors, 2u);
  EXPECT_EQ(registry.protocol(line::kRotctld).errors, 2u);
  EXPECT_EQ(registry.protocol(line::kGs232).errors, 2u);
  EXPECT_EQ(registry.protocol(line::kEasycomm).errors, 1u);
  EXPECT_EQ(registry.protocol(line::kSeed).errors, 1u);
}

TEST(FaultCounters, EachLatchedFaultCountsOnceAndAgainAfterAReset) {
  rotord::testing::FakeRotator r;  // the pot never moves: a go-to stalls
  ASSERT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
  r.run_ms(10000);
  ASSERT_EQ(r.controller->status().az.fault, AxisFault::kStall);
  r.run_ms(1000);  // still latched: not counted again
  EXPECT_EQ(r.controller->faults_latched(AxisId::kAz, AxisFault::kStall), 1u);
  ASSERT_EQ(r.controller->reset(), Error::kOk);
  ASSERT_EQ(r.controller->go_to(200.0f, std::nullopt), Error::kOk);
  r.run_ms(10000);
  EXPECT_EQ(r.controller->faults_latched(AxisId::kAz, AxisFault::kStall), 2u);
  EXPECT_EQ(r.controller->faults_latched(AxisId::kEl, AxisFault::kStall), 0u);
  r.el.adc.counts = 0;  // the el pot's wiper at the rail
  r.run_ms(1000);
  EXPECT_EQ(r.controller->faults_latched(AxisId::kEl, AxisFault::kSensorRange), 1u);
}

TEST(SaverCounters, FailedWritesAreCounted) {
  rotord::testing::MemoryStorage storage;
  settings::Settings values;
  const settings::Settings base;
  char buf[web::Api::kMaxDocumentBytes];
  SettingsSaver saver(values, base, storage, buf, sizeof buf);
  saver.begin();
  values.set(settings::Id::kParkAzDeg, 123);
  storage.fail = true;
  EXPECT_EQ(saver.flush(0), SettingsSaver::Result::kFailed);
  EXPECT_EQ(saver.failures(), 1u);
  storage.fail = false;
  EXPECT_EQ(saver.flush(0), SettingsSaver::Result::kSaved);
  EXPECT_EQ(saver.writes(), 1u);
  EXPECT_EQ(saver.failures(), 1u);
}

/// The pages through the HTTP session, with a clock and a tick schedule the
/// test owns.
class MetricsPages : public ::testing::Test {
 protected:
  struct ManualClock final : hal::MonotonicClock {
    std::int64_t us = 1'000'000;
    std::int64_t now_us() const override { return us; }
  };

  MetricsPages() {
    registry.ticks = &ticks;
    registry.clock = &clock;
    registry.settings_writes = &saver.writes();
    registry.settings_failures = &saver.failures();
    registry.start_us = clock.us;
    ticks.start(clock.us);
    saver.begin();
    run_ms(100);
  }
  /// Ticks the way a port's loop does: the schedule, then the controller.
  void run_ms(int ms) {
    for (int n = 0; n < ms / 10; ++n) {
      clock.us = ticks.deadline_us();
      ASSERT_TRUE(ticks.poll(clock.us));
      r.run_ms(10);
    }
  }
  rotord::testing::HttpResponse get(const std::string& path, const std::string& method = "GET") {
    StringSink sink;
    session.receive(method + " " + path + " HTTP/1.1\r\nHost: localhost\r\n\r\n", sink);
    auto rs = rotord::testing::parse_responses(sink.data);
    return rs.empty() ? rotord::testing::HttpResponse{} : rs[0];
  }

  rotord::testing::FakeRotator r;
  ManualClock clock;
  TickScheduler ticks{10'000};
  rotord::testing::MemoryStorage storage;
  char saver_buf[web::Api::kMaxDocumentBytes];
  SettingsSaver saver{r.settings, r.settings, storage, saver_buf, sizeof saver_buf};
  Registry registry;
  web::Api api{web::ApiContext{*r.controller, &saver, nullptr, nullptr, "9.9.9", nullptr, nullptr,
                               &registry}};
  web::HttpSession session{api};
};

TEST_F(MetricsPages, MetricsAreServedAsPrometheusText) {
  ASSERT_EQ(r.controller->go_to(200.0f, 45.0f), Error::kOk);
  run_ms(500);
  registry.protocol(line::kWrc).on_accept();
  registry.on_reply(line::kWrc, "ERROR INVALID AZIMUTH\r\n");
  const auto res = get("/metrics");
  ASSERT_EQ(res.status, 200);
  EXPECT_EQ(res.header("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  EXPECT_EQ(res.header("Content-Length"), std::to_string(res.body.size()));
  const std::string& b = res.body;
  for (const char* line : {
           "rotord_build_info{version=\"9.9.9\"} 1\n",
           "rotord_axis_position_degrees{axis=\"az\"} 100\n",
           "rotord_axis_target_degrees{axis=\"az\"} 200\n",
           "rotord_axis_target_degrees{axis=\"el\"} 45\n",
           "rotord_axis_state{axis=\"az\",state=\"moving\"} 1\n",
           "rotord_axis_fault{axis=\"az\",kind=\"stall\"} 0\n",
           "rotord_axis_faults_total{axis=\"el\",kind=\"sensor_lost\"} 0\n",
           "rotord_axis_moves_total{axis=\"az\"} 1\n",
           "rotord_axis_output{axis=\"az\",channel=\"relay_cw\"} 1\n",
           "rotord_mode{mode=\"goto\"} 1\n",
           "rotord_connections{protocol=\"wrc\"} 1\n",
           "rotord_connections_accepted_total{protocol=\"wrc\"} 1\n",
           "rotord_protocol_errors_total{protocol=\"wrc\"} 1\n",
           "rotord_connections_evicted_total{protocol=\"http\"} 0\n",
           "rotord_auth_failures_total{protocol=\"http\"} 0\n",
           "rotord_tick_period_seconds 0.01\n",
           "rotord_ticks_total 60\n",
           "rotord_tick_overruns_total 0\n",
           "rotord_tick_interval_seconds_sum 0.59\n",
           "rotord_settings_saves_total 0\n",
           "rotord_settings_save_failures_total 0\n",
           "rotord_uptime_seconds 0.6\n",
       })
    EXPECT_NE(b.find(line), std::string::npos) << line << "\n" << b;
  // Every family is declared once, before its samples.
  EXPECT_EQ(b.rfind("# TYPE rotord_axis_state gauge"), b.find("# TYPE rotord_axis_state gauge"));
  EXPECT_LT(b.find("# TYPE rotord_axis_state gauge"), b.find("rotord_axis_state{"));
}

TEST_F(MetricsPages, HeadGivesTheLengthAndNoBodyOtherMethodsAre405) {
  const auto full = get("/metrics");
  const auto head = get("/metrics", "HEAD");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.header("Content-Length"), full.header("Content-Length"));
  EXPECT_TRUE(head.body.empty());
  StringSink sink;
  session.receive(rotord::testing::post_request("/metrics", "{}"), sink);
  auto rs = rotord::testing::parse_responses(sink.data);
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].status, 405);
  EXPECT_EQ(rs[0].header("Allow"), "GET, HEAD");
}

TEST_F(MetricsPages, WithoutARegistryTheControllersMetricsStillAre) {
  web::Api bare{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "1"}};
  web::HttpSession s{bare};
  StringSink sink;
  s.receive("GET /metrics HTTP/1.1\r\nHost: localhost\r\n\r\n", sink);
  EXPECT_NE(sink.data.find("rotord_axis_position_degrees{axis=\"az\"}"), std::string::npos);
  EXPECT_EQ(sink.data.find("rotord_ticks_total"), std::string::npos);
}

TEST_F(MetricsPages, HealthyWhileTheLoopTicksAndNoSensorFails) {
  const auto res = get("/healthz");
  EXPECT_EQ(res.status, 200);
  EXPECT_EQ(res.body, "{\"status\":\"ok\"}");
}

TEST_F(MetricsPages, UnhealthyWhenTheLoopStopsTicking) {
  clock.us += 250'000;  // the loop has not ticked for 250 ms
  const auto res = get("/healthz");
  EXPECT_EQ(res.status, 503);
  EXPECT_EQ(res.body,
            "{\"status\":\"unhealthy\",\"reason\":\"the control loop has not ticked for 250 "
            "ms\"}");
  run_ms(10);  // ticking again
  EXPECT_EQ(get("/healthz").status, 200);
}

TEST_F(MetricsPages, BeforeTheFirstTickTheTimeSinceStartCounts) {
  TickScheduler fresh(10'000);
  fresh.start(clock.us);
  registry.ticks = &fresh;
  registry.start_us = clock.us;
  clock.us += 5'000;  // started, first tick not yet due
  EXPECT_EQ(get("/healthz").status, 200);
  clock.us += 150'000;  // it never came
  const auto res = get("/healthz");
  EXPECT_EQ(res.status, 503);
  EXPECT_NE(res.body.find("has not ticked for 155 ms"), std::string::npos) << res.body;
}

TEST_F(MetricsPages, UnhealthyWithAPositionSensorFaultButNotWithAStall) {
  r.el.adc.counts = 0;  // the el pot's wiper at the rail
  run_ms(1000);
  ASSERT_EQ(r.controller->status().el.fault, AxisFault::kSensorRange);
  auto res = get("/healthz");
  EXPECT_EQ(res.status, 503);
  EXPECT_NE(res.body.find("el position sensor fault: sensor_range"), std::string::npos) << res.body;
  r.el.set_deg(20);
  ASSERT_EQ(r.controller->reset(), Error::kOk);
  run_ms(100);
  ASSERT_EQ(get("/healthz").status, 200);
  // A stall is a fault of the rotator, not of the controller's senses.
  ASSERT_EQ(r.controller->go_to(300.0f, std::nullopt), Error::kOk);
  run_ms(10000);
  ASSERT_EQ(r.controller->status().az.fault, AxisFault::kStall);
  EXPECT_EQ(get("/healthz").status, 200);
  EXPECT_NE(get("/metrics").body.find("rotord_axis_stalls_total{axis=\"az\"} 1\n"),
            std::string::npos);
}

}  // namespace
}  // namespace rotord::metrics
