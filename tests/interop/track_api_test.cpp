// Tracking over REST with curl against the real daemon (issue 13): TLEs
// pasted with PUT /api/tle (stored in tles.txt beside the settings, across a
// restart), bad TLEs refused, passes, and a track started, followed and
// ended, all on the manual clock with --utc-start (UTC = start + controller
// time), so a 20-minute pass takes no 20 minutes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

namespace fs = std::filesystem;

constexpr const char* kIss =
    "ISS (ZARYA)\n"
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991\n"
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482\n";

class TrackApi : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("rotord-track-api-" + std::to_string(::getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
    config = (dir / "conf" / "settings.json").string();
    std::ofstream(dir / "iss.tle") << kIss;
  }
  void TearDown() override {
    daemon.reset();
    fs::remove_all(dir);
  }
  void start(const std::string& utc_start, const std::string& profile = "g5500") {
    daemon.reset();
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", profile, "--clock", "manual", "--utc-start", utc_start, "--config", config});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    base = "http://127.0.0.1:" + std::to_string(daemon->ports().web);
  }
  void station(double lat, double lon, double alt) {
    const std::string r =
        curl("--json '{\"station.lat_deg\":" + std::to_string(lat) +
             ",\"station.lon_deg\":" + std::to_string(lon) +
             ",\"station.alt_m\":" + std::to_string(alt) + "}' " + base + "/api/settings");
    ASSERT_EQ(status_of(r), 200) << r;
  }
  void advance(long long ms) { ASSERT_GE(daemon->advance_ms(ms), 0) << daemon->output(); }

  fs::path dir;
  std::string config;
  std::unique_ptr<DaemonProcess> daemon;
  std::string base;
};

TEST_F(TrackApi, TlesArePastedListedKeptAcrossARestartAndBadOnesRefused) {
  start("2019-12-09T19:15:00Z");
  std::string r =
      curl("-X PUT --data-binary @" + (dir / "iss.tle").string() + " " + base + "/api/tle");
  ASSERT_EQ(status_of(r), 200) << r;
  EXPECT_NE(r.find("\"added\":1"), std::string::npos) << r;
  EXPECT_TRUE(fs::exists(dir / "conf" / "tles.txt"));
  r = curl(base + "/api/tle");
  EXPECT_EQ(status_of(r), 200);
  EXPECT_NE(r.find("\"name\":\"ISS (ZARYA)\""), std::string::npos) << r;
  EXPECT_NE(r.find("\"catalog\":25544"), std::string::npos) << r;

  // A checksum error: 422 naming the set and the line, nothing stored.
  std::string bad = kIss;
  bad[bad.find("9991")] = '7';
  std::ofstream(dir / "bad.tle") << bad;
  r = curl("-X PUT --data-binary @" + (dir / "bad.tle").string() + " " + base + "/api/tle");
  EXPECT_EQ(status_of(r), 422) << r;
  EXPECT_NE(r.find("set 1: checksum in line 1"), std::string::npos) << r;
  // Not a TLE at all; an object decayed long before the clock's 2019.
  r = curl("-X PUT --data-binary 'hello world' " + base + "/api/tle");
  EXPECT_EQ(status_of(r), 422) << r;
  EXPECT_NE(r.find("belongs to no element set"), std::string::npos) << r;
  std::ofstream(dir / "old.tle")
      << "1 88888U          80275.98708465  .00073094  13844-3  66816-4 0    87\n"
         "2 88888  72.8435 115.9689 0086731  52.6988 110.5714 16.05824518  1058\n";
  r = curl("-X PUT --data-binary @" + (dir / "old.tle").string() + " " + base + "/api/tle");
  EXPECT_EQ(status_of(r), 422) << r;
  EXPECT_NE(r.find("cannot propagate"), std::string::npos) << r;
  // A bad TLE never starts a track: it was never stored.
  r = curl("--json '{\"object\":\"88888\"}' " + base + "/api/track");
  EXPECT_EQ(status_of(r), 404) << r;
  // Methods.
  EXPECT_EQ(status_of(curl("-X POST --json '{}' " + base + "/api/tle")), 405);

  // The store survives a restart.
  start("2019-12-09T19:15:00Z");
  r = curl(base + "/api/tle");
  EXPECT_NE(r.find("\"catalog\":25544"), std::string::npos) << r;
  EXPECT_EQ(status_of(curl("-X DELETE '" + base + "/api/tle?object=25544'")), 200);
  EXPECT_EQ(curl(base + "/api/tle").find("25544"), std::string::npos);
}

TEST_F(TrackApi, PassesOfASatelliteAndOfTheSun) {
  start("2019-12-09T19:15:00Z");
  station(39.86366, -119.17875, 0.0);
  ASSERT_EQ(status_of(curl("-X PUT --data-binary @" + (dir / "iss.tle").string() + " " + base +
                           "/api/tle")),
            200);
  std::string r = curl("'" + base + "/api/passes?object=ISS%20(ZARYA)&hours=6'");
  ASSERT_EQ(status_of(r), 200) << r;
  // The same pass rotord passes prints (docs/tracking.md), 87.8 deg.
  EXPECT_NE(r.find("\"aos_utc\":\"2019-12-09T19:26:15Z\""), std::string::npos) << r;
  EXPECT_NE(r.find("\"max_el_deg\":87.79"), std::string::npos) << r;
  r = curl("'" + base + "/api/passes?object=sun&hours=24'");
  ASSERT_EQ(status_of(r), 200) << r;
  EXPECT_NE(r.find("\"aos_utc\":\"2019-12-10T"), std::string::npos) << r;
  EXPECT_EQ(status_of(curl("'" + base + "/api/passes?object=nothing'")), 404);
  EXPECT_EQ(status_of(curl("'" + base + "/api/passes'")), 400);
  EXPECT_EQ(status_of(curl("'" + base + "/api/passes?object=sun&hours=1000'")), 422);
}

TEST_F(TrackApi, ASatelliteIsTrackedAtItsNextPassAndStopEndsATrack) {
  start("2019-12-09T19:15:00Z");
  station(39.86366, -119.17875, 0.0);
  ASSERT_EQ(status_of(curl("-X PUT --data-binary @" + (dir / "iss.tle").string() + " " + base +
                           "/api/tle")),
            200);
  // "now": the ISS is below the horizon at 19:15.
  std::string r =
      curl("--json '{\"object\":\"ISS (ZARYA)\",\"when\":\"now\"}' " + base + "/api/track");
  EXPECT_EQ(status_of(r), 409) << r;
  EXPECT_NE(r.find("below"), std::string::npos) << r;
  r = curl("--json '{\"object\":\"25544\",\"when\":\"next\"}' " + base + "/api/track");
  ASSERT_EQ(status_of(r), 200) << r;
  EXPECT_NE(r.find("\"armed\":true"), std::string::npos) << r;
  advance(2000);
  r = curl(base + "/api/track");
  EXPECT_NE(r.find("\"phase\":\"waiting\""), std::string::npos) << r;
  EXPECT_NE(r.find("\"aos_utc\":\"2019-12-09T19:26:15Z\""), std::string::npos) << r;
  EXPECT_NE(curl(base + "/api/status").find("\"mode\":\"track\""), std::string::npos);
  // To the middle of the pass: the antenna follows.
  advance((16 * 60 + 38) * 1000);  // 19:31:40
  r = curl(base + "/api/track");
  EXPECT_NE(r.find("\"phase\":\"tracking\""), std::string::npos) << r;
  const double target_el = json_number(body_of(r), "el", body_of(r).find("\"antenna_target\""));
  const std::string s = curl(base + "/api/status");
  // The axis object is the status's last "el" (the odometer has one too).
  const double el = json_number(body_of(s), "position_deg", body_of(s).rfind("\"el\":{"));
  EXPECT_NEAR(el, target_el, 8.0) << r << s;
  // After LOS the track is done.
  advance(7 * 60 * 1000);
  r = curl(base + "/api/track");
  EXPECT_NE(r.find("\"phase\":\"done\""), std::string::npos) << r;
  // The Sun is up (11:38 in Nevada): tracked now; a fixed direction
  // replaces that track and holds; STOP ends it.
  r = curl("--json '{\"body\":\"sun\",\"when\":\"now\"}' " + base + "/api/track");
  EXPECT_EQ(status_of(r), 200) << r;
  advance(3000);
  r = curl(base + "/api/track");
  EXPECT_NE(r.find("\"phase\":\"tracking\""), std::string::npos) << r;
  r = curl("--json '{\"az\":120,\"el\":30}' " + base + "/api/track");
  ASSERT_EQ(status_of(r), 200) << r;
  EXPECT_NE(r.find("\"phase\":\"holding\""), std::string::npos) << r;
  ASSERT_EQ(status_of(curl("-X POST " + base + "/api/stop")), 200);
  r = curl(base + "/api/track");
  EXPECT_NE(r.find("\"armed\":false"), std::string::npos) << r;
  // DELETE /api/track ends a track too.
  ASSERT_EQ(status_of(curl("--json '{\"body\":\"moon\"}' " + base + "/api/track")), 200);
  r = curl("-X DELETE " + base + "/api/track");
  EXPECT_EQ(status_of(r), 200) << r;
  EXPECT_NE(r.find("\"armed\":false"), std::string::npos) << r;
  // Bad requests.
  EXPECT_EQ(status_of(curl("--json '{}' " + base + "/api/track")), 400);
  EXPECT_EQ(status_of(curl("--json '{\"body\":\"mars\"}' " + base + "/api/track")), 422);
  EXPECT_EQ(
      status_of(curl("--json '{\"object\":\"25544\",\"when\":\"later\"}' " + base + "/api/track")),
      422);
  EXPECT_EQ(status_of(curl("--json '{\"az\":500,\"el\":30}' " + base + "/api/track")), 422);
}

}  // namespace
}  // namespace rotord::testing
