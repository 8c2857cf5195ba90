// The Pico W's access::Crypto (ports/pico_w/pico_crypto.cpp) and its mbedtls
// configuration (ports/pico_w/config/mbedtls_config.h) on ARMv6-M code under
// qemu, against an mbedtls 3.6 source tree (the pico-sdk's version), which
// Debian does not package: built only when ROTORD_MBEDTLS3_SOURCE_DIR names
// one (tests/embedded/README.md). The same vectors as the Linux port's test.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "access/pbkdf2.hpp"
#include "pico_crypto.hpp"
#include "util/hex.hpp"

// The pico-sdk's pico_mbedtls.c feeds mbedtls from pico_rand; qemu has no
// pico_rand, so this stand-in counts. Only the plumbing is under test here.
extern "C" int mbedtls_hardware_poll(void*, unsigned char* output, std::size_t len,
                                     std::size_t* olen) {
  static std::uint32_t state = 12345;
  for (std::size_t n = 0; n < len; ++n) {
    state = state * 1664525u + 1013904223u;
    output[n] = static_cast<unsigned char>(state >> 24);
  }
  *olen = len;
  return 0;
}

namespace rotord::pico_w {
namespace {

std::string hex_of(std::span<const std::uint8_t> bytes) {
  std::string s(2 * bytes.size(), '?');
  hex::encode(bytes, s.data());
  return s;
}

TEST(PicoCrypto, HmacSha256MatchesRfc4231) {
  PicoCrypto crypto;
  ASSERT_TRUE(crypto.begin());
  access::Sha256Digest mac;
  ASSERT_TRUE(crypto.hmac_sha256(access::bytes_of("Jefe"),
                                 access::bytes_of("what do ya want for nothing?"), mac));
  EXPECT_EQ(hex_of(mac), "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

// The M0+'s SysTick, for an instruction count: under `qemu -icount shift=0`
// one instruction is 1 ns of virtual time and SysTick runs at the board's
// 25 MHz, so a tick is 40 instructions. Without -icount it means nothing.
volatile std::uint32_t& reg(std::uintptr_t address) {
  return *reinterpret_cast<volatile std::uint32_t*>(address);
}

TEST(PicoCrypto, SlicedPbkdf2MatchesRfc7914) {
  PicoCrypto crypto;
  ASSERT_TRUE(crypto.begin());
  access::Pbkdf2 job;
  job.start("passwd", access::bytes_of("salt"), 1);
  ASSERT_EQ(job.step(crypto, 4), access::Pbkdf2::Status::kDone);
  EXPECT_EQ(hex_of(job.key()), "55ac046e56e3089fec1691c22544b605f94185216dde0465e68b9d57c20dacbc");
  // 1000 iterations in slices of 4, timed by SysTick.
  reg(0xE000E014) = 0x00FFFFFF;  // SYST_RVR
  reg(0xE000E018) = 0;           // SYST_CVR
  reg(0xE000E010) = 5;           // SYST_CSR: enable, processor clock
  const std::uint32_t start = reg(0xE000E018);
  job.start("password", access::bytes_of("0123456789abcdef"), 1000);
  while (job.step(crypto, 4) == access::Pbkdf2::Status::kRunning) {
  }
  const std::uint32_t ticks = (start - reg(0xE000E018)) & 0x00FFFFFF;
  ASSERT_EQ(job.status(), access::Pbkdf2::Status::kDone);
  std::printf(
      "pico_crypto: %lu SysTick ticks for 1000 iterations (x 40 = instructions "
      "under -icount shift=0)\n",
      static_cast<unsigned long>(ticks));
}

TEST(PicoCrypto, RandomBytesAndConstantTimeEquality) {
  PicoCrypto crypto;
  ASSERT_TRUE(crypto.begin());
  std::set<std::string> seen;
  for (int n = 0; n < 50; ++n) {
    std::array<std::uint8_t, 16> bytes{};
    ASSERT_TRUE(crypto.random(bytes));
    EXPECT_TRUE(seen.insert(hex_of(bytes)).second);
  }
  const std::uint8_t a[] = {1, 2, 3};
  const std::uint8_t b[] = {1, 2, 4};
  EXPECT_TRUE(crypto.equal(a, a));
  EXPECT_FALSE(crypto.equal(a, b));
  EXPECT_FALSE(crypto.equal(a, std::span<const std::uint8_t>(b, 2)));
}

TEST(PicoCrypto, WithoutBeginEverythingFails) {
  PicoCrypto crypto;
  std::array<std::uint8_t, 4> bytes{};
  access::Sha256Digest mac;
  EXPECT_FALSE(crypto.random(bytes));
  EXPECT_FALSE(crypto.hmac_sha256(bytes, bytes, mac));
}

}  // namespace
}  // namespace rotord::pico_w
