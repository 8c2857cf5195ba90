// Web and REST access control through the HTTP session and the REST API, on
// a controller with fake hardware and the test crypto (fake_crypto.hpp):
// the password, logins and their limits, cookies, tokens and their scopes,
// the control lock on the web and on a line protocol, STOP for everyone.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "fake_crypto.hpp"
#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "memory_storage.hpp"
#include "protocol/wrc_session.hpp"
#include "web/http_session.hpp"

namespace rotord::web {
namespace {

using rotord::testing::HttpResponse;
using rotord::testing::MemoryStorage;
using rotord::testing::parse_responses;
using rotord::testing::StringSink;
using settings::Id;

constexpr const char* kPassword = "correct horse";

class HttpAccess : public ::testing::Test {
 protected:
  HttpAccess() {
    defaults = r.settings;
    r.run_ms(50);
    api.poll(now);
  }

  ApiContext context() {
    ApiContext c{*r.controller, &storage, &defaults, nullptr, "9.9.9"};
    c.crypto = &crypto;
    c.pbkdf2_iterations = 3000;  // few (the least a stored hash may have is 1000): fast tests
    c.pbkdf2_slice = 1000;       // three polls per hash
    c.log = &log;
    return c;
  }

  rotord::testing::FakeRotator r;
  settings::Settings defaults;
  MemoryStorage storage;
  rotord::testing::FakeCrypto crypto;
  StringSink log;
  Millis now = 1000;
  Api api{context()};

  /// One request on a fresh connection from `peer`; a pending answer is
  /// polled out (the port's loop: api.poll, then the session's poll).
  HttpResponse request(const std::string& bytes,
                       access::Peer peer = access::Peer::from_ipv4(0x0A000002)) {
    HttpSession session(api);
    session.set_peer(peer);
    StringSink sink;
    session.receive(bytes, sink);
    for (int n = 0; n < 20 && sink.data.empty(); ++n) {
      now += 10;
      api.poll(now);
      session.poll(now, sink);
    }
    auto rs = parse_responses(sink.data);
    return rs.empty() ? HttpResponse{} : rs[0];
  }
  static std::string head(const std::string& method, const std::string& path,
                          const std::string& extra) {
    return method + " " + path + " HTTP/1.1\r\nHost: localhost\r\n" + extra;
  }
  HttpResponse get(const std::string& path, const std::string& extra = "") {
    return request(head("GET", path, extra) + "\r\n");
  }
  HttpResponse post(const std::string& path, const std::string& body, const std::string& extra = "",
                    access::Peer peer = access::Peer::from_ipv4(0x0A000002)) {
    return request(head("POST", path, extra) +
                       "Content-Type: application/json\r\nContent-Length: " +
                       std::to_string(body.size()) + "\r\n\r\n" + body,
                   peer);
  }
  /// "Cookie: rotord_session=...\r\n" from a response's Set-Cookie.
  static std::string cookie_from(const HttpResponse& res) {
    const std::string set = res.header("Set-Cookie");
    return "Cookie: " + set.substr(0, set.find(';')) + "\r\n";
  }
  std::string turn_on() {
    const HttpResponse res =
        post("/api/password", std::string(R"({"password":")") + kPassword + "\"}");
    EXPECT_EQ(res.status, 200) << res.body;
    return cookie_from(res);
  }
  std::string make_token(const std::string& cookie, const std::string& name,
                         const std::string& scope) {
    const HttpResponse res =
        post("/api/tokens", R"({"name":")" + name + R"(","scope":")" + scope + "\"}", cookie);
    EXPECT_EQ(res.status, 201) << res.body;
    const auto at = res.body.find("rtd_");
    return "Authorization: Bearer " + res.body.substr(at, 36) + "\r\n";
  }
  static bool has(const HttpResponse& res, const std::string& text) {
    return res.body.find(text) != std::string::npos;
  }
};

TEST_F(HttpAccess, OffByDefaultEverythingAnswersAsBefore) {
  EXPECT_EQ(get("/api/status").status, 200);
  EXPECT_EQ(get("/").status, 200);
  EXPECT_EQ(post("/api/goto", R"({"az":200})").status, 200);
  const HttpResponse auth = get("/api/auth");
  EXPECT_TRUE(has(auth, R"("enabled":false)")) << auth.body;
  EXPECT_EQ(post("/api/login", R"({"password":"x"})").status, 409);
}

TEST_F(HttpAccess, SettingThePasswordTurnsItOnAndLogsTheSetterIn) {
  const HttpResponse res = post("/api/password", R"({"password":"correct horse"})");
  ASSERT_EQ(res.status, 200) << res.body;
  const std::string set = res.header("Set-Cookie");
  EXPECT_NE(set.find("rotord_session="), std::string::npos);
  EXPECT_NE(set.find("; HttpOnly"), std::string::npos) << set;
  EXPECT_NE(set.find("; SameSite=Strict"), std::string::npos) << set;
  EXPECT_NE(set.find("; Path=/"), std::string::npos) << set;
  EXPECT_NE(set.find("; Max-Age=43200"), std::string::npos) << set;  // web.session_minutes
  // Stored as a hash, never read back, saved.
  EXPECT_EQ(r.settings.text(Id::kWebPassword).substr(0, 19), "pbkdf2-sha256$3000$");
  EXPECT_NE(storage.document.find("pbkdf2-sha256$"), std::string::npos);
  const HttpResponse doc = get("/api/settings", cookie_from(res));
  EXPECT_TRUE(has(doc, R"("web.password":"********")")) << doc.body;
  EXPECT_FALSE(has(doc, "pbkdf2"));
  EXPECT_EQ(get("/api/settings", cookie_from(res)).status, 200);
  const HttpResponse anonymous = get("/api/status");
  EXPECT_EQ(anonymous.status, 401);
  EXPECT_EQ(anonymous.header("WWW-Authenticate"), "Bearer realm=\"rotord\"");
  EXPECT_NE(log.data.find("web password set by 10.0.0.2"), std::string::npos) << log.data;
}

TEST_F(HttpAccess, PasswordsBreakingTheRuleAreRefused) {
  EXPECT_EQ(post("/api/password", R"({"password":"short"})").status, 422);
  EXPECT_EQ(post("/api/settings", R"({"web.password":"plain text"})").status, 422);
  EXPECT_FALSE(WebAuth::enabled(r.settings));
}

TEST_F(HttpAccess, LoginWithTheRightPasswordOnlyAndFailuresAreLimitedAndLogged) {
  turn_on();
  const HttpResponse wrong = post("/api/login", R"({"password":"wrong horse"})");
  EXPECT_EQ(wrong.status, 401);
  EXPECT_EQ(wrong.header("Set-Cookie"), "");
  const HttpResponse right = post("/api/login", R"({"password":"correct horse"})");
  ASSERT_EQ(right.status, 200);
  EXPECT_EQ(get("/api/status", cookie_from(right)).status, 200);
  EXPECT_EQ(get("/settings.html", cookie_from(right)).status, 200);
  // A guess every 6 s: within the strangers' budget (10 a minute).
  for (int n = 0; n < 3; ++n) {
    now += 6000;
    api.poll(now);
    EXPECT_EQ(post("/api/login", R"({"password":"guess"})").status, 401);
  }
  // Three in a row: this address waits 1 s, and the strangers' budget 6 s.
  const HttpResponse held = post("/api/login", R"({"password":"correct horse"})");
  EXPECT_EQ(held.status, 429);
  EXPECT_EQ(held.header("Retry-After"), "6");
  EXPECT_NE(held.body.find("too many failed logins"), std::string::npos) << held.body;
  // Another address is not held up.
  now += 6000;
  api.poll(now);
  EXPECT_EQ(
      post("/api/login", R"({"password":"correct horse"})", "", access::Peer::from_ipv4(0x0A000003))
          .status,
      200);
  EXPECT_EQ(api.auth().failed_logins(), 4u);
  // The first failure from an address in a minute is logged, the rest summed
  // up when the minute ends (no client floods the log).
  EXPECT_NE(log.data.find("failed web login from 10.0.0.2 (1 in a row)"), std::string::npos)
      << log.data;
  EXPECT_EQ(log.data.find("(3 in a row)"), std::string::npos) << log.data;
  now += 60000;
  api.poll(now);
  EXPECT_NE(log.data.find("rotord: 3 more from 10.0.0.2 in the last minute"), std::string::npos)
      << log.data;
}

TEST_F(HttpAccess, StopAndTheLoginPageNeedNoLoginEverythingElseDoes) {
  turn_on();
  r.controller->go_to(300.0f, std::nullopt);
  EXPECT_EQ(post("/api/stop", "").status, 200);
  EXPECT_EQ(get("/login.html").status, 200);
  EXPECT_EQ(get("/login.js").status, 200);
  EXPECT_EQ(get("/style.css").status, 200);
  const HttpResponse page = get("/");
  EXPECT_EQ(page.status, 303);
  EXPECT_EQ(page.header("Location"), "/login.html");
  EXPECT_EQ(get("/control.js").status, 401);
  EXPECT_EQ(get("/api/events").status, 401);
  EXPECT_EQ(post("/api/goto", R"({"az":10})").status, 401);
  EXPECT_EQ(post("/api/settings", R"({"park.az_deg":10})").status, 401);
  EXPECT_EQ(post("/api/password", R"({"password":""})").status, 401);
  EXPECT_EQ(post("/api/lock", "{}").status, 401);
  EXPECT_EQ(
      get("/api/status", "Cookie: rotord_session=00000000000000000000000000000000\r\n").status,
      401);
}

TEST_F(HttpAccess, TokensReadOrControlShownOnceStoredHashed) {
  const std::string cookie = turn_on();
  const std::string reader = make_token(cookie, "logger", "read");
  const std::string driver = make_token(cookie, "gpredict", "control");
  EXPECT_EQ(get("/api/status", reader).status, 200);
  EXPECT_EQ(post("/api/goto", R"({"az":100})", reader).status, 403);
  EXPECT_EQ(post("/api/stop", "", reader).status, 200);
  EXPECT_EQ(post("/api/goto", R"({"az":100})", driver).status, 200);
  // Access rules, secrets and tokens need the web login.
  EXPECT_EQ(post("/api/settings", R"({"access.control_networks":"10.0.0.0/8"})", driver).status,
            403);
  EXPECT_EQ(post("/api/settings", R"({"wifi.password":"12345678"})", driver).status, 403);
  EXPECT_EQ(post("/api/settings", R"({"park.az_deg":10})", driver).status, 200);
  EXPECT_EQ(post("/api/tokens", R"({"name":"more"})", driver).status, 403);
  EXPECT_EQ(post("/api/password", R"({"password":""})", driver).status, 403);
  // Listed by name and scope; the settings show neither tokens nor hashes.
  const HttpResponse list = get("/api/tokens", cookie);
  EXPECT_TRUE(has(list, R"({"name":"logger","scope":"read"})")) << list.body;
  const HttpResponse doc = get("/api/settings", cookie);
  EXPECT_TRUE(has(doc, R"("web.token_1":"********")")) << doc.body;
  EXPECT_FALSE(has(doc, "rtd_"));
  EXPECT_FALSE(has(doc, "logger"));
  EXPECT_EQ(post("/api/tokens", R"({"name":"logger"})", cookie).status, 409);  // name taken
  // Revoked: refused from then on.
  EXPECT_EQ(post("/api/tokens/revoke", R"({"name":"logger"})", cookie).status, 200);
  EXPECT_EQ(get("/api/status", reader).status, 401);
  EXPECT_EQ(get("/api/status", "Authorization: Bearer rtd_nonsense\r\n").status, 401);
  EXPECT_EQ(get("/api/status", "Authorization: Basic dXNlcjpwYXNz\r\n").status, 401);
}

TEST_F(HttpAccess, TwoAuthorizationHeadersAreABadRequest) {
  EXPECT_EQ(get("/api/status", "Authorization: Bearer a\r\nAuthorization: Bearer b\r\n").status,
            400);
}

TEST_F(HttpAccess, TheLockLeavesOthersReadOnlyOnTheWebAndTheLineProtocolsButNotStop) {
  const std::string a = turn_on();
  const HttpResponse b_login = post("/api/login", R"({"password":"correct horse"})");
  const std::string b = cookie_from(b_login);
  const HttpResponse locked = post("/api/lock", R"({"minutes":2})", a);
  ASSERT_EQ(locked.status, 200) << locked.body;
  EXPECT_TRUE(has(locked, R"("mine":true)")) << locked.body;
  EXPECT_EQ(post("/api/goto", R"({"az":100})", a).status, 200);
  const HttpResponse refused = post("/api/goto", R"({"az":100})", b);
  EXPECT_EQ(refused.status, 423);
  EXPECT_TRUE(has(refused, "STOP still works")) << refused.body;
  EXPECT_EQ(post("/api/settings", R"({"park.az_deg":10})", b).status, 423);
  EXPECT_EQ(post("/api/unlock", "{}", b).status, 423);
  EXPECT_EQ(post("/api/stop", "", b).status, 200);
  EXPECT_EQ(get("/api/status", b).status, 200);
  EXPECT_TRUE(has(get("/api/auth", b), R"("lock":{"held":true,"mine":false,"by":"web session")"));
  // A line protocol refuses in its own way; STOP goes through.
  protocol::WrcSession wrc(*r.controller, "9.9.9");
  StringSink wrc_out;
  wrc.receive("AZ 10\nSTOP\n", wrc_out);
  EXPECT_EQ(wrc_out.data, "ERROR NOT ALLOWED\r\nOK STOP\r\n");
  // Released by its holder: everyone controls again.
  EXPECT_EQ(post("/api/unlock", "{}", a).status, 200);
  EXPECT_EQ(post("/api/goto", R"({"az":100})", b).status, 200);
}

TEST_F(HttpAccess, TheLockRunsOut) {
  const std::string a = turn_on();
  ASSERT_EQ(post("/api/lock", R"({"minutes":1})", a).status, 200);
  EXPECT_TRUE(r.controller->control_lock().held());
  EXPECT_EQ(post("/api/lock", R"({"minutes":0})", a).status, 422);
  EXPECT_EQ(post("/api/lock", R"({"minutes":241})", a).status, 422);
  now += 60'000;
  api.poll(now);
  EXPECT_FALSE(r.controller->control_lock().held());
  EXPECT_NE(log.data.find("control lock ran out"), std::string::npos);
}

TEST_F(HttpAccess, WithAccessControlOffTheLockBelongsToACookie) {
  const HttpResponse locked = post("/api/lock", "{}");
  ASSERT_EQ(locked.status, 200);
  const std::string mine = cookie_from(locked);
  EXPECT_NE(locked.header("Set-Cookie").find("HttpOnly"), std::string::npos);
  EXPECT_EQ(post("/api/goto", R"({"az":100})").status, 423);
  EXPECT_EQ(post("/api/goto", R"({"az":100})", mine).status, 200);
  EXPECT_EQ(post("/api/stop", "").status, 200);
  // An anonymous session is no login once access control goes on.
  turn_on();
  EXPECT_FALSE(r.controller->control_lock().held());  // a new password releases it
  EXPECT_EQ(get("/api/status", mine).status, 401);
}

TEST_F(HttpAccess, ResettingTheSettingsKeepsThePasswordAndTokens) {
  const std::string cookie = turn_on();
  make_token(cookie, "t", "read");
  ASSERT_EQ(post("/api/settings/reset", "{}", cookie).status, 200);
  EXPECT_TRUE(WebAuth::enabled(r.settings));
  EXPECT_FALSE(r.settings.text(Id::kWebToken1).empty());
  EXPECT_EQ(get("/api/status").status, 401);
  // Turning it off is explicit.
  EXPECT_EQ(post("/api/password", R"({"password":""})", cookie).status, 200);
  EXPECT_EQ(get("/api/status").status, 200);
}

TEST_F(HttpAccess, OneHashAtATimeAndAnAbandonedLoginStillCounts) {
  turn_on();
  {
    HttpSession first(api);
    first.set_peer(access::Peer::from_ipv4(0x0A000009));
    StringSink sink;
    first.receive(rotord::testing::post_request("/api/login", R"({"password":"guess one"})"), sink);
    EXPECT_TRUE(sink.data.empty());  // being hashed
    const HttpResponse busy = post("/api/login", R"({"password":"correct horse"})");
    EXPECT_EQ(busy.status, 503);
    EXPECT_EQ(busy.header("Retry-After"), "1");
  }  // the client left before its answer
  for (int n = 0; n < 5; ++n) api.poll(now += 10);
  EXPECT_EQ(api.auth().failed_logins(), 1u);
  EXPECT_EQ(post("/api/login", R"({"password":"correct horse"})").status, 200);
}

TEST_F(HttpAccess, AnEventStreamEndsWithItsLogin) {
  const std::string cookie = turn_on();
  HttpSession stream(api);
  StringSink sink;
  stream.receive(head("GET", "/api/events", cookie) + "\r\n", sink);
  ASSERT_NE(sink.data.find("200 OK"), std::string::npos) << sink.data;
  stream.poll(now += 1000, sink);
  EXPECT_FALSE(stream.wants_close());
  EXPECT_EQ(post("/api/logout", "{}", cookie).status, 200);
  stream.poll(now += 1000, sink);
  EXPECT_TRUE(stream.wants_close());
}

TEST_F(HttpAccess, TheSchemaHidesTheHashRowsFromTheForm) {
  const HttpResponse schema = get("/api/settings/schema");
  EXPECT_TRUE(has(schema, R"("key":"web.password","type":"password")")) << schema.body.substr(0, 0);
  const auto at = schema.body.find(R"("key":"web.password")");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(schema.body.find(R"("hidden":true)", at), std::string::npos);
}

}  // namespace
}  // namespace rotord::web
