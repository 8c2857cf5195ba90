// Recognising the pass a client follows, through the real daemon and the real
// Hamlib client: the ISS's elements pasted with PUT /api/tle and Boulder set
// as the station, the manual clock at the pass (--utc-start), one `rotctl -m
// 2` session behaves as Gpredict does (a cycle of 1 s of controller time:
// `p`, then `P az el` with the ISS's 0..360 position from `rotord predict`
// when off by more than 5 deg). GET /api/status and /metrics show the
// recognition; a go-to away from the ISS ends it and is obeyed literally.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "rotctl_session.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

constexpr const char* kIss =
    "ISS (ZARYA)\n"
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991\n"
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482\n";

TEST(Recognition, RotctlStreamingTheIssPassIsRecognisedAndShownInApiStatus) {
  const std::string dir = make_temp_dir("rotord-recognition");
  std::ofstream(dir + "/iss.tle") << kIss;
  // The ISS's pass over Boulder: AOS 22:44:48 at 312 deg, LOS 22:54:15.
  const CommandOutput predict =
      run_command(std::string(ROTORD_BINARY) + " predict --tle " + dir +
                  "/iss.tle --lat 40.015 --lon -105.27 --alt 1655 --from 2019-12-09T22:44:50Z --to "
                  "2019-12-09T22:50:00Z --step 1");
  ASSERT_EQ(predict.rc, 0) << predict.out;
  std::vector<std::pair<double, double>> sky;  // one a second from 22:44:50
  {
    std::istringstream lines(predict.out);
    std::string line;
    std::getline(lines, line);  // the header
    while (std::getline(lines, line)) {
      double az = 0, el = 0;
      if (std::sscanf(line.c_str(), "%*[^,],%lf,%lf", &az, &el) == 2) sky.emplace_back(az, el);
    }
  }
  ASSERT_GT(sky.size(), 300u);

  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual", "--utc-start",
                        "2019-12-09T22:44:50Z", "--config", dir + "/conf/settings.json"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const std::string base = "http://127.0.0.1:" + std::to_string(daemon.ports().web);
  const auto curl = [&](const std::string& args) {
    return run_command("timeout 20 curl -s " + args + " 2>&1").out;
  };
  ASSERT_NE(
      curl("-X PUT --data-binary @" + dir + "/iss.tle " + base + "/api/tle").find("\"added\":1"),
      std::string::npos);
  ASSERT_EQ(curl("-o /dev/null -w '%{http_code}' --json '{\"station.lat_deg\":40.015,"
                 "\"station.lon_deg\":-105.27,\"station.alt_m\":1655}' " +
                 base + "/api/settings"),
            "200");
  EXPECT_NE(curl(base + "/api/status").find("\"recognised\":null"), std::string::npos);

  RotctlSession gpredict("127.0.0.1:" + std::to_string(daemon.ports().rotctld), 120);
  ASSERT_TRUE(gpredict.ok());
  int sent = 0, recognised_at = 0, sent_then = 0, cycle = 0;
  double worst_gap = 0;  // what the client reads against its target, once recognised
  for (; cycle < 240 && cycle < static_cast<int>(sky.size()); ++cycle) {
    const auto [az, el] = sky[static_cast<std::size_t>(cycle)];
    double read_az = 0, read_el = 0;
    ASSERT_TRUE(gpredict.read(read_az, read_el)) << gpredict.text();
    if (recognised_at > 0 && cycle > recognised_at + 60)
      worst_gap = std::fmax(worst_gap, std::fabs(read_az - az));
    if (std::fabs(read_az - az) > 5.0 || std::fabs(read_el - el) > 5.0) {
      char cmd[64];
      std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", az, el);
      gpredict.send(cmd);
      ++sent;
      if (recognised_at == 0 &&
          curl(base + "/api/status").find("\"active\":true") != std::string::npos) {
        recognised_at = cycle;
        sent_then = sent;
      }
    }
    ASSERT_GE(daemon.advance_ms(1000), 0);
  }
  const std::string state = curl(base + "/api/status");
  const std::string metrics = curl(base + "/metrics");
  std::printf(
      "[ recognition ] rotctl, ISS over Boulder: recognised after %d go-tos (cycle %d), "
      "%d go-tos in %d s, the client read at most %.1f deg from its target once "
      "followed\n",
      sent_then, recognised_at, sent, cycle, worst_gap);
  EXPECT_GT(recognised_at, 0) << gpredict.text() << daemon.output();
  EXPECT_NE(state.find("\"recognised\":{\"active\":true,\"object\":\"ISS (ZARYA)\""),
            std::string::npos)
      << state;
  EXPECT_NE(state.find("\"mode\":\"track\""), std::string::npos) << state;
  EXPECT_NE(metrics.find("rotord_goto_recognised_total 1"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find("rotord_goto_recognised{object=\"ISS (ZARYA)\",catalog=\"25544\"} 1"),
            std::string::npos)
      << metrics;
  // Followed between go-tos: the client had little to send, and what it
  // reads stays near its own target.
  EXPECT_LT(sent, 20);
  EXPECT_LT(worst_gap, 5.0);

  // A go-to away from the ISS ends it and is obeyed as sent.
  gpredict.send("P 180 45\n");
  double az = 0, el = 0;
  for (int i = 0; i < 90; ++i) ASSERT_GE(daemon.advance_ms(1000), 0);
  ASSERT_TRUE(gpredict.read(az, el));
  EXPECT_NEAR(az, 180.0, 2.0);
  EXPECT_NEAR(el, 45.0, 2.0);
  const std::string after = curl(base + "/api/status");
  EXPECT_NE(after.find("\"active\":false"), std::string::npos) << after;
  EXPECT_NE(after.find("\"ended\":\"departed\""), std::string::npos) << after;
  EXPECT_NE(daemon.output().find("recognised ISS (ZARYA) (NORAD 25544)"), std::string::npos)
      << daemon.output();
  run_command("rm -rf " + dir);
}

}  // namespace
}  // namespace rotord::testing
