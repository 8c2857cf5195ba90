// GET /metrics and GET /healthz on the real daemon (issue 12), read by the
// real tools: curl fetches, Prometheus' own `promtool check metrics` (Debian
// `prometheus`) must accept the page, and the counters must follow what the
// test does over real sockets (moves, error replies, a refused client).
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

class MetricsEndpoint : public ::testing::Test {
 protected:
  void SetUp() override {
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{"--clock", "manual"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
  }
  std::string url(const std::string& path) const {
    return "http://127.0.0.1:" + std::to_string(daemon->ports().web) + path;
  }
  std::string metrics() { return run_command("timeout 20 curl -sS " + url("/metrics")).out; }
  /// The value of one sample line ("name{labels}"), or -1.
  double sample(const std::string& page, const std::string& series) {
    const auto at = page.find("\n" + series + " ");
    if (at == std::string::npos) return -1;
    return std::stod(page.substr(at + series.size() + 2));
  }
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_F(MetricsEndpoint, PromtoolAcceptsThePage) {
  TcpClient wrc(daemon->ports().wrc);
  ASSERT_EQ(wrc.ask("AZ 300\n"), "OK AZ 300.00");
  ASSERT_GT(daemon->advance_ms(2000), 0);
  const std::string dir = make_temp_dir("rotord-metrics");
  const std::string file = dir + "/metrics.txt";
  const CommandOutput fetched =
      run_command("timeout 20 curl -sSf -o " + file + " " + url("/metrics"));
  ASSERT_EQ(fetched.rc, 0) << fetched.out;
  const CommandOutput check = run_command("timeout 20 promtool check metrics < " + file);
  EXPECT_EQ(check.rc, 0) << check.out;
  EXPECT_EQ(check.out, "");  // not even a lint warning
  run_command("rm -rf " + dir);

  // The tick schedule as it ran: printed, not asserted (tests never assert
  // wall-clock timing; `make bench` measures).
  const std::string page = metrics();
  const double sum = sample(page, "rotord_tick_interval_seconds_sum");
  const double count = sample(page, "rotord_tick_interval_seconds_count");
  EXPECT_EQ(sample(page, "rotord_tick_period_seconds"), 0.01);
  if (count > 0)
    std::printf("tick period as run: %.4f ms mean over %.0f intervals, %.0f overruns\n",
                sum / count * 1000, count, sample(page, "rotord_tick_overruns_total"));
}

TEST_F(MetricsEndpoint, CountersFollowWhatClientsDo) {
  TcpClient wrc(daemon->ports().wrc);
  ASSERT_EQ(wrc.ask("AZ 300\n"), "OK AZ 300.00");
  EXPECT_EQ(wrc.ask("AZ 9999\n"), "ERROR INVALID AZIMUTH");
  EXPECT_EQ(wrc.ask("BOGUS\n"), "ERROR INVALID COMMAND");
  ASSERT_GT(daemon->advance_ms(3000), 0);
  // Seven more clients from seven other hosts (one host holds at most
  // net.max_per_address) fill the WRC limit (net.max_clients 8); a ninth,
  // with nobody idle for net.idle_evict_s, is refused.
  std::vector<std::unique_ptr<TcpClient>> others;
  for (int n = 0; n < 7; ++n) {
    others.push_back(
        std::make_unique<TcpClient>(daemon->ports().wrc, "127.0.0." + std::to_string(n + 2)));
    ASSERT_EQ(others.back()->ask("AZ?\n").substr(0, 5), "OK AZ");
  }
  TcpClient refused(daemon->ports().wrc, "127.0.0.20");
  std::string line;
  ASSERT_TRUE(refused.read_line(line));
  ASSERT_EQ(line, "ERROR TOO MANY CONNECTIONS");

  const std::string page = metrics();
  EXPECT_EQ(sample(page, "rotord_connections{protocol=\"wrc\"}"), 8) << page;
  EXPECT_EQ(sample(page, "rotord_connections_accepted_total{protocol=\"wrc\"}"), 8);
  EXPECT_EQ(sample(page, "rotord_connections_refused_total{protocol=\"wrc\"}"), 1);
  EXPECT_EQ(sample(page, "rotord_protocol_errors_total{protocol=\"wrc\"}"), 2);
  EXPECT_EQ(sample(page, "rotord_connections{protocol=\"http\"}"), 1);  // curl itself
  EXPECT_EQ(sample(page, "rotord_axis_target_degrees{axis=\"az\"}"), 300);
  EXPECT_EQ(sample(page, "rotord_axis_state{axis=\"az\",state=\"moving\"}"), 1);
  EXPECT_EQ(sample(page, "rotord_axis_moves_total{axis=\"az\"}"), 1);
  EXPECT_EQ(sample(page, "rotord_axis_output{axis=\"az\",channel=\"relay_cw\"}"), 1);
  EXPECT_GT(sample(page, "rotord_axis_position_degrees{axis=\"az\"}"), 200);

  // A 404 is an HTTP error reply.
  run_command("timeout 20 curl -s " + url("/nothing-here"));
  EXPECT_EQ(sample(metrics(), "rotord_protocol_errors_total{protocol=\"http\"}"), 1);
}

TEST_F(MetricsEndpoint, HealthzSaysOkAndWhyNot) {
  CommandOutput ok = run_command("timeout 20 curl -s -w ' %{http_code}' " + url("/healthz"));
  EXPECT_EQ(ok.out, "{\"status\":\"ok\"} 200");

  // A G-5500 told its azimuth has an MA3 encoder: the sensor is not there.
  const std::string dir = make_temp_dir("rotord-healthz");
  const std::string config = dir + "/settings.json";
  std::FILE* f = std::fopen(config.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("{\"settings_version\": 2, \"az.sensor\": \"ma3\"}\n", f);
  std::fclose(f);
  daemon = std::make_unique<DaemonProcess>(
      std::vector<std::string>{"--clock", "manual", "--config", config});
  ASSERT_TRUE(daemon->ready()) << daemon->output();
  CommandOutput bad = run_command("timeout 20 curl -s -w ' %{http_code}' " + url("/healthz"));
  EXPECT_EQ(bad.out,
            "{\"status\":\"unhealthy\",\"reason\":\"az position sensor fault: no_sensor\"} "
            "503");
  daemon.reset();
  run_command("rm -rf " + dir);
}

}  // namespace
}  // namespace rotord::testing
