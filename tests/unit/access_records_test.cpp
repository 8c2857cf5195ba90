// The pieces of web and REST access control, each on its own: the stored
// password hash and token formats, the Cookie header, sessions, the
// failed-login limiter, the control lock, PBKDF2's slicing.
#include <gtest/gtest.h>

#include <string>

#include "access/api_token.hpp"
#include "access/control_lock.hpp"
#include "access/login_limiter.hpp"
#include "access/password_hash.hpp"
#include "access/pbkdf2.hpp"
#include "access/web_sessions.hpp"
#include "fake_crypto.hpp"
#include "util/hex.hpp"

namespace rotord::access {
namespace {

using rotord::testing::FakeCrypto;

TEST(PasswordHash, TextFormRoundTrips) {
  PasswordHash h;
  h.iterations = 100000;
  for (std::size_t n = 0; n < h.salt.size(); ++n) h.salt[n] = static_cast<std::uint8_t>(n);
  for (std::size_t n = 0; n < h.key.size(); ++n) h.key[n] = static_cast<std::uint8_t>(0xf0 + n);
  char text[PasswordHash::kMaxTextBytes + 1];
  const std::size_t len = format_password_hash(h, text, sizeof text);
  EXPECT_EQ(std::string(text, len),
            "pbkdf2-sha256$100000$000102030405060708090a0b0c0d0e0f$"
            "f0f1f2f3f4f5f6f7f8f9fafbfcfdfeff");
  PasswordHash back;
  ASSERT_TRUE(parse_password_hash(text, back));
  EXPECT_EQ(back.iterations, h.iterations);
  EXPECT_EQ(back.salt, h.salt);
  EXPECT_EQ(back.key, h.key);
  EXPECT_EQ(format_password_hash(h, text, 20), 0u);  // no room: nothing
}

TEST(PasswordHash, AnythingButTheTextFormIsRefused) {
  const std::string salt(32, 'a');
  const std::string key(32, 'b');
  PasswordHash h;
  EXPECT_TRUE(parse_password_hash("pbkdf2-sha256$1000$" + salt + "$" + key, h));
  for (const std::string& bad : {
           std::string("hunter22"),                              // a password, not a hash
           "pbkdf2-sha1$1000$" + salt + "$" + key,               // another algorithm
           "pbkdf2-sha256$999$" + salt + "$" + key,              // too few iterations
           "pbkdf2-sha256$10000001$" + salt + "$" + key,         // too many
           "pbkdf2-sha256$01000$" + salt + "$" + key,            // leading zero
           "pbkdf2-sha256$$" + salt + "$" + key,                 // no count
           "pbkdf2-sha256$1000$" + salt + key,                   // no separator
           "pbkdf2-sha256$1000$" + salt + "$" + key + "0",       // key too long
           "pbkdf2-sha256$1000$" + salt.substr(1) + "g$" + key,  // not hex
       })
    EXPECT_FALSE(parse_password_hash(bad, h)) << bad;
}

TEST(PasswordHash, NewPasswordsFollowTheRule) {
  EXPECT_EQ(password_rule_violation("12345678"), nullptr);
  EXPECT_NE(password_rule_violation("1234567"), nullptr);
  EXPECT_NE(password_rule_violation(std::string(64, 'x')), nullptr);
  EXPECT_EQ(password_rule_violation(std::string(63, 'x')), nullptr);
  EXPECT_NE(password_rule_violation("tab\there1"), nullptr);
}

TEST(ApiToken, RecordsRoundTripAndRefuseBadText) {
  TokenRecord r;
  std::memcpy(r.name, "gpredict", 9);
  r.scope = Scope::kControl;
  r.hash.fill(0xab);
  char text[80];
  const std::size_t len = format_token_record(r, text, sizeof text);
  EXPECT_EQ(std::string(text, len), "gpredict:control:abababababababababababababababab");
  TokenRecord back;
  ASSERT_TRUE(parse_token_record(text, back));
  EXPECT_STREQ(back.name, "gpredict");
  EXPECT_EQ(back.scope, Scope::kControl);
  EXPECT_EQ(back.hash, r.hash);
  const std::string hash(32, '0');
  for (const std::string& bad :
       {"gpredict:write:" + hash, ":read:" + hash, std::string(17, 'n') + ":read:" + hash,
        "a b:read:" + hash, "x:read:" + hash.substr(2), std::string("x:read"), std::string("x")})
    EXPECT_FALSE(parse_token_record(bad, back)) << bad;
}

TEST(ApiToken, MadeTokensDifferAndHashToTheirRecord) {
  FakeCrypto crypto;
  char a[kTokenTextBytes + 1];
  char b[kTokenTextBytes + 1];
  std::array<std::uint8_t, TokenRecord::kHashBytes> ha{}, hb{}, check{};
  ASSERT_TRUE(make_token(crypto, a, ha));
  ASSERT_TRUE(make_token(crypto, b, hb));
  EXPECT_EQ(std::string(a).substr(0, 4), "rtd_");
  EXPECT_EQ(std::string(a).size(), kTokenTextBytes);
  EXPECT_NE(std::string(a), std::string(b));
  EXPECT_NE(ha, hb);
  ASSERT_TRUE(hash_token(crypto, a, check));
  EXPECT_EQ(check, ha);
  crypto.random_works = false;
  EXPECT_FALSE(make_token(crypto, a, ha));  // no random bytes: no token
}

TEST(Cookies, TheNamedCookieIsFoundAmongOthers) {
  EXPECT_EQ(cookie_value("rotord_session=abc", "rotord_session"), "abc");
  EXPECT_EQ(cookie_value("a=1; rotord_session=abc; b=2", "rotord_session"), "abc");
  EXPECT_EQ(cookie_value("a=1;rotord_session=\"abc\"", "rotord_session"), "abc");
  EXPECT_EQ(cookie_value("rotord_session=first; rotord_session=second", "rotord_session"), "first");
  EXPECT_EQ(cookie_value("xrotord_session=abc; rotord_sessionx=d", "rotord_session"), "");
  EXPECT_EQ(cookie_value("", "rotord_session"), "");
  EXPECT_EQ(cookie_value(";;;=;rotord_session", "rotord_session"), "");
}

std::string cookie_of(const WebSessions& s, int index) {
  char id[WebSessions::kIdTextBytes + 1];
  s.id_text(index, id);
  return std::string("rotord_session=") + id;
}

TEST(WebSessions, FoundByCookieUntilExpiryOrRemoval) {
  FakeCrypto crypto;
  WebSessions s;
  const int a = s.create(crypto, 1000, 60000, true);
  const int b = s.create(crypto, 1000, 60000, false);
  ASSERT_GE(a, 0);
  ASSERT_NE(a, b);
  EXPECT_EQ(s.find(crypto, cookie_of(s, a), 2000), a);
  EXPECT_EQ(s.find(crypto, "x=1; " + cookie_of(s, b), 2000), b);
  EXPECT_TRUE(s.at(a).authenticated);
  EXPECT_FALSE(s.at(b).authenticated);
  EXPECT_EQ(s.find(crypto, "rotord_session=" + std::string(32, '0'), 2000), -1);
  EXPECT_EQ(s.find(crypto, "rotord_session=zz", 2000), -1);
  EXPECT_EQ(s.find(crypto, cookie_of(s, a), 61000), -1);  // expired
  const std::string gone = cookie_of(s, b);
  s.remove(b);
  EXPECT_EQ(s.find(crypto, gone, 2000), -1);
  crypto.random_works = false;
  EXPECT_EQ(s.create(crypto, 3000, 60000, true), -1);
}

TEST(WebSessions, TheOldestMakesRoomWhenFull) {
  FakeCrypto crypto;
  WebSessions s;
  std::string first;
  for (Millis n = 0; n < static_cast<Millis>(WebSessions::kMax); ++n) {
    const int i = s.create(crypto, 100 + n, 60000, true);
    if (n == 0) first = cookie_of(s, i);
  }
  const int newest = s.create(crypto, 500, 60000, true);
  EXPECT_GE(s.find(crypto, cookie_of(s, newest), 600), 0);
  EXPECT_EQ(s.find(crypto, first, 600), -1);
}

TEST(LoginLimiter, ThreeFreeFailuresThenAWaitThatDoubles) {
  LoginLimiter l;
  const Peer a = Peer::from_ipv4(0xC0A80114);
  const Peer b = Peer::from_ipv4(0xC0A80115);
  EXPECT_EQ(l.wait_ms(a, 0), 0);
  EXPECT_EQ(l.failed(a, 0), 1u);
  EXPECT_EQ(l.failed(a, 0), 2u);
  EXPECT_EQ(l.wait_ms(a, 0), 0);
  l.failed(a, 0);
  EXPECT_EQ(l.wait_ms(a, 0), 1000);
  EXPECT_EQ(l.wait_ms(b, 0), 0);  // another address is not held up
  l.failed(a, 1000);
  EXPECT_EQ(l.wait_ms(a, 1000), 2000);
  l.failed(a, 3000);
  EXPECT_EQ(l.wait_ms(a, 3000), 4000);
  for (int n = 0; n < 20; ++n) l.failed(a, 10000);
  EXPECT_EQ(l.wait_ms(a, 10000), LoginLimiter::kMaxWaitMs);
  l.succeeded(a);
  EXPECT_EQ(l.wait_ms(a, 10000), 0);
}

TEST(LoginLimiter, ANewAddressReplacesTheOneIdleLongest) {
  LoginLimiter l;
  for (std::uint32_t n = 0; n < LoginLimiter::kAddresses; ++n)
    for (int k = 0; k < 3; ++k) l.failed(Peer::from_ipv4(n), 100 + n);
  l.failed(Peer::from_ipv4(1000), 200);
  EXPECT_EQ(l.wait_ms(Peer::from_ipv4(0), 100), 0);  // forgotten
  EXPECT_GT(l.wait_ms(Peer::from_ipv4(7), 107), 0);  // kept
}

TEST(ControlLock, HeldByOneUntilReleasedOrRunOut) {
  ControlLock lock;
  LockHolder a;
  a.key = {1, 2, 3, 4, 5, 6, 7, 8};
  LockHolder b = a;
  b.key[7] = 9;
  LockHolder token = a;
  token.kind = LockHolder::Kind::kToken;
  EXPECT_FALSE(lock.held());
  lock.take(a, 5000);
  EXPECT_TRUE(lock.held_by(a));
  EXPECT_FALSE(lock.held_by(b));
  EXPECT_FALSE(lock.held_by(token));  // same bytes, another kind
  lock.expire(4999);
  EXPECT_TRUE(lock.held());
  lock.expire(5000);
  EXPECT_FALSE(lock.held());
  lock.take(b, 9000);
  lock.release();
  EXPECT_FALSE(lock.held_by(b));
}

TEST(Pbkdf2, TheSliceSizeDoesNotChangeTheKey) {
  FakeCrypto crypto;
  const std::uint8_t salt[] = {1, 2, 3, 4};
  Sha256Digest whole{};
  for (std::uint32_t slice : {1u, 7u, 1000u}) {
    Pbkdf2 job;
    job.start("password", salt, 100);
    int slices = 0;
    while (job.step(crypto, slice) == Pbkdf2::Status::kRunning) ++slices;
    ASSERT_EQ(job.status(), Pbkdf2::Status::kDone);
    EXPECT_EQ(slices + 1, static_cast<int>((100 + slice - 1) / slice));
    if (slice == 1) whole = job.key();
    EXPECT_EQ(job.key(), whole);
  }
  EXPECT_EQ(crypto.hmac_calls, 300);  // one HMAC per iteration, no more
}

}  // namespace
}  // namespace rotord::access
