// The log cannot be flooded (issue 29, item 6), through the real daemon: 2000
// requests with random bearer tokens on one keep-alive connection. Prints
// the log bytes a minute under the flood.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"

namespace rotord::testing {
namespace {

/// Sends one request on `c` and reads its whole response; the status.
int round_trip(TcpClient& c, const std::string& request) {
  if (!c.send(request)) return 0;
  std::string got;
  for (int n = 0; n < 50; ++n) {
    got += c.recv_once(200);
    const auto head_end = got.find("\r\n\r\n");
    if (head_end == std::string::npos) continue;
    const auto length_at = got.find("Content-Length: ");
    const std::size_t length = length_at == std::string::npos
                                   ? 0
                                   : std::strtoul(got.c_str() + length_at + 16, nullptr, 10);
    if (got.size() >= head_end + 4 + length) break;
  }
  return got.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(got.c_str() + 9) : 0;
}

TEST(LogFlood, RandomBearerTokensOnOneConnectionWriteTwoLinesAMinute) {
  const std::string dir = make_temp_dir("rotord-flood");
  DaemonProcess daemon({"--sim", "g5500", "--clock", "manual", "--config", dir + "/settings.json"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  const int web = daemon.ports().web;
  ASSERT_EQ(http(web, "POST", "/api/password", R"({"password": "correct horse battery"})").status,
            200);
  daemon.advance_ms(10);
  const std::size_t before = daemon.output().size();

  TcpClient c(web, "127.0.0.5");
  int refused = 0;
  std::srand(29);
  for (int n = 0; n < 2000; ++n) {
    char token[33];
    for (char& ch : token) ch = "0123456789abcdef"[std::rand() % 16];
    token[32] = '\0';
    const int status = round_trip(c, std::string("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                                 "Authorization: Bearer rtd_") +
                                         token + "\r\n\r\n");
    if (status == 401) ++refused;
  }
  EXPECT_EQ(refused, 2000);
  daemon.advance_ms(60000);  // the minute ends: one summary line
  daemon.advance_ms(10);
  // What rotord logged (the manual clock's own replies aside).
  std::string logged;
  const std::string all = daemon.output().substr(before);
  for (std::size_t at = 0; at < all.size();) {
    const std::size_t end = std::min(all.find('\n', at), all.size() - 1) + 1;
    const std::string line = all.substr(at, end - at);
    if (line.rfind("rotord: clock ", 0) != 0) logged += line;
    at = end;
  }
  std::printf(
      "[ measured ] 2000 requests with random bearer tokens: %zu log bytes in the minute "
      "(%d refused)\n%s",
      logged.size(), refused, logged.c_str());
  EXPECT_NE(logged.find("unknown bearer token from 127.0.0.5 refused"), std::string::npos);
  EXPECT_NE(logged.find("1999 more from 127.0.0.5 in the last minute"), std::string::npos)
      << logged;
  EXPECT_LT(logged.size(), 400u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rotord::testing
