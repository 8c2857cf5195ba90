// The wear odometer through the real daemon (issue 27, docs/care.md):
// shown in /metrics and /api/status, kept across a restart and a power cut
// (kill -9: at most one save interval, 60 s, lost), a damaged counter file
// starts again from zero without blocking the start, a reset is dated.
#include <stdlib.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

class Odometer : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir[] = "/tmp/rotord-odometer-XXXXXX";
    ASSERT_NE(::mkdtemp(dir), nullptr);
    dir_ = dir;
  }
  void TearDown() override { run_command("rm -rf " + dir_); }

  std::vector<std::string> args() const {
    return {"--sim", "g5500", "--clock", "manual", "--config", dir_ + "/settings.json"};
  }
  std::string read(const std::string& name) const {
    std::ifstream in(dir_ + "/" + name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  /// Starts of the azimuth as GET /api/odometer says.
  static double az_starts(DaemonProcess& d) {
    const HttpResponse r = http(d.ports().web, "GET", "/api/odometer");
    EXPECT_EQ(r.status, 200) << r.body;
    return json_number(r.body, "starts", r.body.find("\"az\""));
  }
  /// Two go-tos (out and back: the G-5500 starts at 225), run out in
  /// controller time.
  static void turn(DaemonProcess& d) {
    ASSERT_EQ(http(d.ports().web, "POST", "/api/goto", R"({"az": 120})").status, 200);
    d.advance_ms(40000);
    ASSERT_EQ(http(d.ports().web, "POST", "/api/goto", R"({"az": 200})").status, 200);
    d.advance_ms(30000);
  }

  std::string dir_;
};

TEST_F(Odometer, ShownInMetricsAndStatusAndKeptAcrossARestart) {
  double starts = 0.0;
  {
    DaemonProcess d(args());
    ASSERT_TRUE(d.ready()) << d.output();
    EXPECT_NE(d.output().find("no odometer at"), std::string::npos) << d.output();
    turn(d);
    starts = az_starts(d);
    EXPECT_GE(starts, 2.0);
    const HttpResponse m = http(d.ports().web, "GET", "/metrics");
    EXPECT_NE(m.body.find("rotord_odometer_starts_total{axis=\"az\"} " +
                          std::to_string(static_cast<int>(starts))),
              std::string::npos)
        << m.body;
    EXPECT_NE(m.body.find("rotord_odometer_reversals_total{axis=\"az\"} 1"), std::string::npos);
    const HttpResponse s = http(d.ports().web, "GET", "/api/status");
    const std::size_t odo = s.body.find("\"odometer\"");
    ASSERT_NE(odo, std::string::npos) << s.body;
    EXPECT_EQ(json_number(s.body, "starts", odo), starts) << s.body;
    EXPECT_EQ(d.terminate(), 0);
  }
  EXPECT_NE(read("odometer.json").find("\"az.starts\":" + std::to_string(static_cast<int>(starts))),
            std::string::npos)
      << read("odometer.json");
  DaemonProcess again(args());
  ASSERT_TRUE(again.ready()) << again.output();
  EXPECT_NE(again.output().find("odometer loaded from"), std::string::npos) << again.output();
  EXPECT_EQ(az_starts(again), starts);
  // A restart is not a start: nothing counted, and counting goes on.
  turn(again);
  EXPECT_GE(az_starts(again), starts + 2.0);
}

TEST_F(Odometer, APowerCutLosesAtMostOneSaveInterval) {
  double saved_starts = 0.0;
  {
    DaemonProcess d(args());
    ASSERT_TRUE(d.ready()) << d.output();
    turn(d);
    d.advance_ms(61000);  // a save interval passes: written
    saved_starts = az_starts(d);
    ASSERT_GE(saved_starts, 2.0);
    EXPECT_EQ(d.stop_with(SIGKILL), 128 + SIGKILL);  // the power cut: no shutdown save
  }
  DaemonProcess again(args());
  ASSERT_TRUE(again.ready()) << again.output();
  EXPECT_EQ(az_starts(again), saved_starts);
}

TEST_F(Odometer, ADamagedCounterFileStartsFromZeroAndNeverBlocksTheStart) {
  std::ofstream(dir_ + "/odometer.json") << R"({"format":1,"az.starts":12,"az.rev)";
  DaemonProcess d(args());
  ASSERT_TRUE(d.ready()) << d.output();
  EXPECT_NE(d.output().find("is damaged (not a JSON object): counting again from zero"),
            std::string::npos)
      << d.output();
  EXPECT_EQ(az_starts(d), 0.0);
  turn(d);
  EXPECT_EQ(d.terminate(), 0);
  // Replaced by a valid record; the damaged one kept for a look.
  EXPECT_NE(read("odometer.json").find("\"az.starts\":"), std::string::npos);
  EXPECT_NE(read("odometer.json.bad").find("\"az.starts\":12"), std::string::npos);
}

TEST_F(Odometer, AResetIsDatedAndWrittenAtOnce) {
  DaemonProcess d(args());
  ASSERT_TRUE(d.ready()) << d.output();
  turn(d);
  ASSERT_GE(az_starts(d), 1.0);
  const HttpResponse r = http(d.ports().web, "POST", "/api/odometer/reset", "");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(json_number(r.body, "starts", r.body.find("\"az\"")), 0.0) << r.body;
  EXPECT_NE(r.body.find("\"reset_utc\":\"20"), std::string::npos) << r.body;
  d.advance_ms(10);  // one pass of the loop: the saver writes a reset at once
  EXPECT_NE(read("odometer.json").find("\"az.starts\":0"), std::string::npos);
  EXPECT_EQ(read("odometer.json").find("\"reset_unix_s\":0"), std::string::npos);
}

}  // namespace
}  // namespace rotord::testing
