// The set-up endpoints (docs/commissioning.md) through the real daemon over
// real sockets: the model list, a model filling the settings, and a whole
// self-commissioning run on the simulated Ham IV in controller time
// (--clock manual), accepted and saved to the settings file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "daemon_process.hpp"
#include "file_text.hpp"
#include "http_client.hpp"

namespace rotord::testing {
namespace {

namespace fs = std::filesystem;

class SetupApi : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("rotord-setup-api-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    config = dir / "settings.json";
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "ham4", "--clock", "manual", "--config", config.string()});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    port = daemon->ports().web;
  }
  void TearDown() override {
    daemon.reset();
    fs::remove_all(dir);
  }
  /// Runs controller time until the run is no longer "running".
  std::string run_to_end(long long limit_ms) {
    std::string body;
    for (long long t = 0; t < limit_ms; t += 10000) {
      EXPECT_GE(daemon->advance_ms(10000), 0);
      body = http(port, "GET", "/api/commission").body;
      if (body.find("\"state\":\"running\"") == std::string::npos) break;
    }
    return body;
  }

  fs::path dir, config;
  std::unique_ptr<DaemonProcess> daemon;
  int port = 0;
};

TEST_F(SetupApi, ModelListAndAModelFillsTheSettingsWithItsSources) {
  const HttpResponse models = http(port, "GET", "/api/models");
  ASSERT_EQ(models.status, 200);
  EXPECT_NE(models.body.find("\"id\":\"hygain-ham4\",\"name\":\"Hy-Gain HAM IV\""),
            std::string::npos);
  EXPECT_NE(models.body.find("{\"key\":\"az.max_deg\",\"value\":360,\"source\":\"[HG3] 360 deg\"}"),
            std::string::npos)
      << models.body;
  // No published speed: the row says so.
  EXPECT_NE(models.body.find("{\"key\":\"az.speed_deg_s\",\"value\":null,\"source\":null}"),
            std::string::npos);

  const HttpResponse bad = http(port, "POST", "/api/setup/model", R"({"model":"g5500"})");
  EXPECT_EQ(bad.status, 422);
  const HttpResponse ok = http(port, "POST", "/api/setup/model", R"({"model":"spid-ras"})");
  ASSERT_EQ(ok.status, 200) << ok.body;
  EXPECT_NE(ok.body.find("\"az.min_deg\""), std::string::npos) << ok.body;
  EXPECT_NE(read_file(config).find("\"az.min_deg\": -180"), std::string::npos) << read_file(config);
  const HttpResponse settings = http(port, "GET", "/api/settings");
  EXPECT_NE(settings.body.find("\"az.max_deg\":540"), std::string::npos);
}

TEST_F(SetupApi, CommissionsTheHam4AndTheAcceptedProposalIsSaved) {
  EXPECT_EQ(http(port, "POST", "/api/commission", R"({"step":"sideways"})").status, 400);
  EXPECT_EQ(http(port, "POST", "/api/commission/accept", "{}").status, 409);
  // The simulated Ham IV's switches sit 1 deg outside 0..360.
  const HttpResponse started =
      http(port, "POST", "/api/commission", R"({"axis":"az","ccw_deg":-1,"cw_deg":361})");
  ASSERT_EQ(started.status, 200) << started.body;
  EXPECT_NE(started.body.find("\"state\":\"running\""), std::string::npos) << started.body;

  const std::string done = run_to_end(600000);
  ASSERT_NE(done.find("\"state\":\"done\""), std::string::npos) << done;
  EXPECT_NE(done.find("\"swapped\":false"), std::string::npos) << done;
  // The simulated pot reads 0.05 V at 0 deg and 3.0 V at 360 deg (12-bit,
  // 3.3 V): the ends, 1 deg outside, within 1 % of the span.
  const double lo = json_number(done, "value", done.find("\"key\":\"az.pot_cal_lo_counts\""));
  const double hi = json_number(done, "value", done.find("\"key\":\"az.pot_cal_hi_counts\""));
  const double counts_per_deg = (3.0 - 0.05) / 3.3 * 4095.0 / 360.0;
  const double true_lo = 0.05 / 3.3 * 4095.0 - counts_per_deg;
  const double true_hi = 3.0 / 3.3 * 4095.0 + counts_per_deg;
  EXPECT_NEAR(lo, true_lo, 0.01 * (true_hi - true_lo)) << done;
  EXPECT_NEAR(hi, true_hi, 0.01 * (true_hi - true_lo)) << done;
  EXPECT_NEAR(json_number(done, "fast_deg_s"), 6.0, 0.3) << done;
  EXPECT_NE(done.find("\"samples\":[["), std::string::npos);

  const HttpResponse accepted = http(port, "POST", "/api/commission/accept", "{}");
  ASSERT_EQ(accepted.status, 200) << accepted.body;
  EXPECT_NE(accepted.body.find("\"az.pot_cal_lo_counts\""), std::string::npos) << accepted.body;
  EXPECT_NE(read_file(config).find("\"az.pot_cal_lo_counts\""), std::string::npos);
}

TEST_F(SetupApi, StopAbortsARun) {
  ASSERT_EQ(http(port, "POST", "/api/commission", R"({"axis":"az"})").status, 200);
  ASSERT_GE(daemon->advance_ms(5000), 0);
  ASSERT_EQ(http(port, "POST", "/api/stop", "").status, 200);
  const std::string body = http(port, "GET", "/api/commission").body;
  EXPECT_NE(body.find("\"state\":\"aborted\""), std::string::npos) << body;
  EXPECT_NE(body.find("\"reason\":\"STOP\""), std::string::npos) << body;
  EXPECT_EQ(http(port, "POST", "/api/commission", R"({"axis":"el"})").status, 422);
}

}  // namespace
}  // namespace rotord::testing
