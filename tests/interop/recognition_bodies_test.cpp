// Recognising the Sun and the Moon in a client's go-to stream, through the
// real daemon and the real Hamlib client: no TLEs stored, only the station's
// position (Boulder) set over the REST API, the manual clock at a time the
// body is up (--utc-start). One `rotctl -m 2` session behaves as a Sun or
// Moon tracker on a timer does (PstRotator's Sun/Moon tracking, an EME
// script): every 10 s of controller time `p`, then `P az el` with the body's
// position from `rotord predict --body`. GET /api/status, /metrics and the
// log show the recognition; a go-to away from the body ends it and is obeyed
// literally.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "rotctl_session.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

constexpr const char* kBoulder = "--lat 40.015 --lon -105.27 --alt 1655";

/// The body's position once a second from `from_utc`, for `seconds`.
std::vector<std::pair<double, double>> body_path(const std::string& body,
                                                 const std::string& from_utc,
                                                 const std::string& to_utc) {
  const CommandOutput predict =
      run_command(std::string(ROTORD_BINARY) + " predict --body " + body + " " + kBoulder +
                  " --from " + from_utc + " --to " + to_utc + " --step 1");
  std::vector<std::pair<double, double>> path;
  if (predict.rc != 0) return path;
  std::istringstream lines(predict.out);
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    double az = 0, el = 0;
    if (std::sscanf(line.c_str(), "%*[^,],%lf,%lf", &az, &el) == 2) path.emplace_back(az, el);
  }
  return path;
}

struct BodyCase {
  const char* body;         ///< rotord predict --body
  const char* name;         ///< as GET /api/status names it
  const char* kind;         ///< "sun" / "moon"
  const char* from;         ///< the body is up over Boulder
  const char* to;           ///< from + 10 min
  double away_az, away_el;  ///< a go-to far from the body
};

void recognise_and_depart(const BodyCase& bc) {
  const std::vector<std::pair<double, double>> sky = body_path(bc.body, bc.from, bc.to);
  ASSERT_GT(sky.size(), 500u);
  const std::string dir = make_temp_dir("rotord-recognition-bodies");
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual", "--utc-start", bc.from, "--config",
                        dir + "/conf/settings.json"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const int web = daemon.ports().web;
  const auto get = [web](const std::string& path) { return http(web, "GET", path).body; };
  ASSERT_EQ(http(web, "POST", "/api/settings",
                 R"({"station.lat_deg":40.015,"station.lon_deg":-105.27,"station.alt_m":1655})")
                .status,
            200);
  EXPECT_NE(get("/api/status").find("\"recognised\":null"), std::string::npos);

  RotctlSession tracker("127.0.0.1:" + std::to_string(daemon.ports().rotctld), 200);
  ASSERT_TRUE(tracker.ok());
  const std::string active = std::string("\"recognised\":{\"active\":true,\"object\":\"") +
                             bc.name + "\",\"kind\":\"" + bc.kind + "\"";
  int sent = 0, recognised_after = 0;
  double worst_gap = 0;  // what the client reads against the body, once recognised
  for (std::size_t t = 0; t + 10 < sky.size(); t += 10) {
    const auto [az, el] = sky[t];
    double read_az = 0, read_el = 0;
    ASSERT_TRUE(tracker.read(read_az, read_el)) << tracker.text();
    if (recognised_after > 0 && sent > recognised_after + 3)
      worst_gap = std::fmax(worst_gap, std::fmax(std::fabs(read_az - az), std::fabs(read_el - el)));
    char cmd[64];
    std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", az, el);
    tracker.send(cmd);
    ++sent;
    // The first go-to is a slew from park (literal): let it arrive.
    ASSERT_GE(daemon.advance_ms(sent == 1 ? 60000 : 10000), 0);
    if (recognised_after == 0 && get("/api/status").find(active) != std::string::npos)
      recognised_after = sent;
  }
  const std::string state = get("/api/status");
  const std::string metrics = get("/metrics");
  std::printf(
      "[ recognition ] rotctl following the %s: recognised after %d go-tos, %d sent, the client "
      "read at most %.2f deg from the %s once followed\n",
      bc.body, recognised_after, sent, worst_gap, bc.body);
  EXPECT_GT(recognised_after, 0) << state << daemon.output();
  EXPECT_NE(state.find(active), std::string::npos) << state;
  EXPECT_NE(state.find("\"mode\":\"track\""), std::string::npos) << state;
  EXPECT_NE(metrics.find("rotord_goto_recognised_total 1"), std::string::npos) << metrics;
  EXPECT_NE(metrics.find(std::string("rotord_goto_recognised{object=\"") + bc.name +
                         "\",catalog=\"0\"} 1"),
            std::string::npos)
      << metrics;
  EXPECT_LT(worst_gap, 2.0);

  // A go-to away from the body ends the recognition and is obeyed as sent.
  char away[48];
  std::snprintf(away, sizeof away, "P %.1f %.1f\n", bc.away_az, bc.away_el);
  tracker.send(away);
  for (int i = 0; i < 90; ++i) ASSERT_GE(daemon.advance_ms(1000), 0);
  double az = 0, el = 0;
  ASSERT_TRUE(tracker.read(az, el)) << tracker.text();
  EXPECT_NEAR(az, bc.away_az, 2.0);
  EXPECT_NEAR(el, bc.away_el, 2.0);
  const std::string after = get("/api/status");
  EXPECT_NE(after.find("\"active\":false"), std::string::npos) << after;
  EXPECT_NE(after.find("\"ended\":\"departed\""), std::string::npos) << after;
  EXPECT_NE(after.find("\"mode\":\"idle\""), std::string::npos) << after;
  EXPECT_NE(get("/metrics").find("rotord_goto_recognised 0"), std::string::npos);
  const std::string log = daemon.output();
  EXPECT_NE(log.find(std::string("recognised the ") + bc.name + " in a client's go-to stream"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find(std::string("recognised pass of ") + bc.name + " ended: departed"),
            std::string::npos)
      << log;
  run_command("rm -rf " + dir);
}

TEST(RecognitionBodies, RotctlFollowingTheSunIsRecognisedAndADepartingGotoIsObeyed) {
  recognise_and_depart(
      {"sun", "Sun", "sun", "2019-12-09T18:00:00Z", "2019-12-09T18:10:00Z", 300.0, 40.0});
}

TEST(RecognitionBodies, RotctlFollowingTheMoonIsRecognisedAndADepartingGotoIsObeyed) {
  recognise_and_depart(
      {"moon", "Moon", "moon", "2019-12-10T03:00:00Z", "2019-12-10T03:10:00Z", 300.0, 20.0});
}

}  // namespace
}  // namespace rotord::testing
