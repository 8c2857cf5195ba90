// The web's defences against browser attacks (issue 12): DNS rebinding (a
// foreign Host), cross-site requests (a foreign Origin) and framing.
#include "web/host_check.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "web/http_session.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
namespace {

using settings::Id;

TEST(HostCheck, TheDevicesOwnNamesAndAddressesPass) {
  settings::Settings s;  // net.hostname "rotord"
  for (const char* host :
       {"", "rotord", "ROTORD.local", "rotord.local.", "rotord:8080", "rotord.local:80",
        "192.168.1.20", "192.168.1.20:8080", "127.0.0.1", "[::1]", "[fe80::1]:8080", "localhost",
        "localhost:8080", "shackpi", "shackpi.local:8080", "shackpi.example.org"})
    EXPECT_TRUE(host_allowed(host, s, "shackpi.example.org")) << host;
}

TEST(HostCheck, OtherNamesAreRefusedUnlessAllowed) {
  settings::Settings s;
  for (const char* host : {"attacker.example", "attacker.example:8080", "rotord.attacker.example",
                           "rotordx.local", "x", "[::1", "[nothex]", "rotord:80x",
                           "192.168.1.20.attacker.example", ":8080", "localhost.attacker.example"})
    EXPECT_FALSE(host_allowed(host, s, "shackpi")) << host;
  ASSERT_EQ(s.set_text(Id::kWebAllowedHosts, "rotor.example.org, proxy").error, Error::kOk);
  EXPECT_TRUE(host_allowed("rotor.example.org", s, nullptr));
  EXPECT_TRUE(host_allowed("PROXY:443", s, nullptr));
  EXPECT_FALSE(host_allowed("example.org", s, nullptr));
}

TEST(HostCheck, OnlyThePagesOwnOriginMayChangeState) {
  settings::Settings s;
  EXPECT_TRUE(origin_allowed("", "rotord.local", s));  // curl, scripts
  EXPECT_TRUE(origin_allowed("http://rotord.local:8080", "rotord.local:8080", s));
  EXPECT_TRUE(origin_allowed("http://192.168.1.20", "192.168.1.20", s));
  EXPECT_FALSE(origin_allowed("http://evil.example", "rotord.local", s));
  EXPECT_FALSE(origin_allowed("http://192.168.1.99", "192.168.1.20", s));  // another LAN page
  EXPECT_FALSE(origin_allowed("null", "rotord.local", s));
  EXPECT_FALSE(origin_allowed("http://rotord.local/x", "rotord.local", s));
  ASSERT_EQ(s.set_text(Id::kWebAllowedHosts, "rotor.example.org").error, Error::kOk);
  EXPECT_TRUE(origin_allowed("https://rotor.example.org", "127.0.0.1:8080", s));  // a proxy
}

class WebDefences : public ::testing::Test {
 protected:
  testing::FakeRotator r;
  Api api{ApiContext{*r.controller, nullptr, nullptr, nullptr, "9"}};
  HttpSession session{api};
  testing::HttpResponse send(const std::string& bytes) {
    testing::StringSink sink;
    session.receive(bytes, sink);
    const auto responses = testing::parse_responses(sink.data);
    return responses.empty() ? testing::HttpResponse{} : responses.front();
  }
};

TEST_F(WebDefences, AForeignHostGets421AndNothingMoves) {
  const testing::HttpResponse res = send(
      "POST /api/goto HTTP/1.1\r\nHost: attacker.example\r\nContent-Type: "
      "application/json\r\nContent-Length: 11\r\n\r\n{\"az\": 200}");
  EXPECT_EQ(res.status, 421);
  EXPECT_NE(res.body.find("web.allowed_hosts"), std::string::npos) << res.body;
  EXPECT_FALSE(r.controller->status().az.has_target);
  EXPECT_EQ(send("GET / HTTP/1.1\r\nHost: attacker.example\r\n\r\n").status, 421);
}

TEST_F(WebDefences, AForeignOriginGets403ButReadsStillWork) {
  const testing::HttpResponse res = send(
      "POST /api/goto HTTP/1.1\r\nHost: rotord.local\r\nOrigin: http://evil.example\r\n"
      "Content-Type: application/json\r\nContent-Length: 11\r\n\r\n{\"az\": 200}");
  EXPECT_EQ(res.status, 403);
  EXPECT_FALSE(r.controller->status().az.has_target);
  EXPECT_EQ(send("GET /api/status HTTP/1.1\r\nHost: rotord.local\r\nOrigin: http://evil.example"
                 "\r\n\r\n")
                .status,
            200);
}

TEST_F(WebDefences, TwoHostHeadersAreRefused) {
  EXPECT_EQ(send("GET / HTTP/1.1\r\nHost: rotord\r\nHost: attacker.example\r\n\r\n").status, 400);
}

TEST_F(WebDefences, EveryResponseForbidsFramingAndForeignContent) {
  for (const char* request : {"GET / HTTP/1.1\r\nHost: rotord\r\n\r\n",
                              "GET /api/status HTTP/1.1\r\nHost: rotord\r\n\r\n",
                              "GET /nope HTTP/1.1\r\nHost: rotord\r\n\r\n"}) {
    const testing::HttpResponse res = send(request);
    EXPECT_EQ(res.header("X-Frame-Options"), "DENY") << request;
    const std::string csp = res.header("Content-Security-Policy");
    EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos) << csp;
    EXPECT_NE(csp.find("default-src 'self'"), std::string::npos) << csp;
    EXPECT_EQ(res.header("X-Content-Type-Options"), "nosniff");
  }
}

}  // namespace
}  // namespace rotord::web
