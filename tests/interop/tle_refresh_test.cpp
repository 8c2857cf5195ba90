// TLE refresh from a URL (track.tle_url) with libcurl, against a local HTTP
// server (python3's http.server): the stored objects are updated from the
// download, others and bad sets are left out, a failing URL is logged.
// Waits on the wall clock: the download is a real HTTP transfer on a thread.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "daemon_process.hpp"
#include "poll.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

namespace fs = std::filesystem;

/// Appends the modulo-10 checksum to a 68-character TLE line.
std::string with_checksum(const std::string& line68) {
  int sum = 0;
  for (const char c : line68) {
    if (c >= '0' && c <= '9') sum += c - '0';
    if (c == '-') sum += 1;
  }
  return line68 + static_cast<char>('0' + sum % 10);
}

const std::string kOld1 = "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991";
const std::string kOld2 = "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482";

class TleRefresh : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = make_temp_dir("rotord-tle-refresh");
    fs::create_directories(fs::path(dir) / "www");
    http_port = free_port();
    server = ::fork();
    if (server == 0) {
      ::execlp("python3", "python3", "-m", "http.server", "--bind", "127.0.0.1", "--directory",
               (dir + "/www").c_str(), std::to_string(http_port).c_str(), nullptr);
      ::_exit(127);
    }
    // The server (another process) is ready when it answers.
    const std::string server_url = "http://127.0.0.1:" + std::to_string(http_port) + "/";
    poll_until([&] { return run_command("curl -s -o /dev/null " + server_url).rc == 0; },
               std::chrono::seconds(10));
    daemon = std::make_unique<DaemonProcess>(
        std::vector<std::string>{"--sim", "g5500", "--clock", "manual", "--utc-start",
                                 "2019-12-09T19:00:00Z", "--config", dir + "/conf/settings.json"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    base = "http://127.0.0.1:" + std::to_string(daemon->ports().web);
  }
  void TearDown() override {
    daemon.reset();
    if (server > 0) {
      ::kill(server, SIGTERM);
      ::waitpid(server, nullptr, 0);
    }
    fs::remove_all(dir);
  }
  std::string curl(const std::string& args) {
    return run_command("timeout 20 curl -s " + args + " 2>&1").out;
  }
  /// GET /api/tle until it holds `text` (bounded: the download runs on the
  /// wall clock).
  bool tles_show(const std::string& text) {
    return poll_until([&] { return curl(base + "/api/tle").find(text) != std::string::npos; },
                      std::chrono::seconds(10));
  }

  std::string dir;
  int http_port = 0;
  pid_t server = -1;
  std::unique_ptr<DaemonProcess> daemon;
  std::string base;
};

TEST_F(TleRefresh, StoredObjectsAreUpdatedFromTheUrlAndOthersLeftOut) {
  std::ofstream(dir + "/old.tle") << "ISS (ZARYA)\n" << kOld1 << "\n" << kOld2 << "\n";
  ASSERT_NE(
      curl("-X PUT --data-binary @" + dir + "/old.tle " + base + "/api/tle").find("\"added\":1"),
      std::string::npos);
  // The download: newer ISS elements (epoch 19344.5), an object not stored
  // here (an Alpha-5 number, catalog 100001), and a set with a bad checksum.
  const std::string new1 =
      with_checksum("1 25544U 98067A   19344.50000000  .00001764  00000-0  38792-4 0  999");
  const std::string alpha1 =
      with_checksum("1 A0001U 98067A   19344.50000000  .00001764  00000-0  38792-4 0  999");
  const std::string alpha2 =
      with_checksum("2 A0001  51.6439 211.2001 0007417  17.6667  85.6398 15.5010347220248");
  std::string bad1 = kOld1;
  bad1.replace(2, 5, "25545");  // the checksum no longer matches
  std::ofstream(dir + "/www/gp.txt") << "ISS (ZARYA)\r\n"
                                     << new1 << "\r\n"
                                     << kOld2 << "\r\n"
                                     << "NEW ONE\r\n"
                                     << alpha1 << "\r\n"
                                     << alpha2 << "\r\n"
                                     << "BROKEN\r\n"
                                     << bad1 << "\r\n"
                                     << kOld2 << "\r\n";
  const std::string url = "http://127.0.0.1:" + std::to_string(http_port) + "/gp.txt";
  ASSERT_NE(curl("--json '{\"track.tle_url\":\"" + url + "\"}' " + base + "/api/settings")
                .find("\"ok\":true"),
            std::string::npos);
  EXPECT_TRUE(tles_show("19344.50000000")) << daemon->output();
  EXPECT_TRUE(daemon->wait_for_output("1 updated, 1 not stored here, 1 bad")) << daemon->output();
  const std::string list = curl(base + "/api/tle");
  EXPECT_EQ(list.find("A0001"), std::string::npos) << list;
  EXPECT_NE(list.find("\"name\":\"ISS (ZARYA)\""), std::string::npos) << list;
  // Kept in tles.txt.
  std::ifstream saved(dir + "/conf/tles.txt");
  const std::string text((std::istreambuf_iterator<char>(saved)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("19344.50000000"), std::string::npos) << text;

  // A URL that fails is logged and changes nothing.
  curl("--json '{\"track.tle_url\":\"http://127.0.0.1:" + std::to_string(http_port) +
       "/missing.txt\"}' " + base + "/api/settings");
  EXPECT_TRUE(daemon->wait_for_output("failed: HTTP status 404")) << daemon->output();
  EXPECT_NE(curl(base + "/api/tle").find("19344.50000000"), std::string::npos);
  // Other schemes are refused by libcurl's protocol list.
  curl("--json '{\"track.tle_url\":\"file:///etc/passwd\"}' " + base + "/api/settings");
  EXPECT_TRUE(daemon->wait_for_output("/etc/passwd failed")) << daemon->output();
}

}  // namespace
}  // namespace rotord::testing
