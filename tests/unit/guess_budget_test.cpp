// The login guess budget and the device cookie (issue 29, item 4).
#include <gtest/gtest.h>

#include "access/device_cookie.hpp"
#include "access/guess_budget.hpp"
#include "fake_crypto.hpp"

namespace rotord::access {
namespace {

TEST(GuessBudget, TenAMinuteAfterABurstOfTwo) {
  GuessBudget b;
  int checked = 0;
  Millis last = 0;
  // Someone tries every 100 ms for ten minutes.
  for (Millis now = 0; now < 600000; now += 100) {
    if (b.wait_ms(now) > 0) continue;
    b.spend(now);
    ++checked;
    last = now;
  }
  EXPECT_EQ(checked, 101);  // 2 at once, then one every 6 s
  EXPECT_GT(b.wait_ms(last), 0);
  EXPECT_LE(b.wait_ms(last), GuessBudget::kIntervalMs);
}

TEST(GuessBudget, AQuietSpellGivesTheBurstBackNotMore) {
  GuessBudget b;
  b.spend(0);
  b.spend(0);
  EXPECT_GT(b.wait_ms(0), 0);
  EXPECT_EQ(b.wait_ms(3600000), 0);
  b.spend(3600000);
  b.spend(3600000);
  EXPECT_GT(b.wait_ms(3600000), 0);
}

}  // namespace
}  // namespace rotord::access

namespace rotord::access {
namespace {

PasswordHash hash_with_key(std::uint8_t fill) {
  PasswordHash h;
  h.iterations = 1000;
  h.key.fill(fill);
  return h;
}

TEST(DeviceCookie, OnlyTheControllerWithThePasswordHashMakesOne) {
  testing::FakeCrypto crypto;
  const PasswordHash stored = hash_with_key(7);
  char value[DeviceCookie::kTextBytes + 1];
  ASSERT_TRUE(DeviceCookie::make(crypto, stored, value));
  const std::string header = "rotord_session=abc; rotord_device=" + std::string(value);
  EXPECT_TRUE(DeviceCookie::valid(crypto, stored, header));
  // Another password: not this one's.
  EXPECT_FALSE(DeviceCookie::valid(crypto, hash_with_key(8), header));
  // One digit of the tag changed, or the nonce: refused.
  std::string forged = header;
  forged.back() = forged.back() == '0' ? '1' : '0';
  EXPECT_FALSE(DeviceCookie::valid(crypto, stored, forged));
  forged = header;
  forged[forged.find("rotord_device=") + 14] ^= 1;
  EXPECT_FALSE(DeviceCookie::valid(crypto, stored, forged));
  EXPECT_FALSE(DeviceCookie::valid(crypto, stored, "rotord_device="));
  EXPECT_FALSE(DeviceCookie::valid(crypto, stored, ""));
  // No random numbers: no cookie.
  crypto.random_works = false;
  EXPECT_FALSE(DeviceCookie::make(crypto, stored, value));
}

}  // namespace
}  // namespace rotord::access
