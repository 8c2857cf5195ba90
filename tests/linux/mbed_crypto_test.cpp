// The Linux port's crypto (Debian's mbedtls) against published vectors, and
// the core's sliced PBKDF2 on it against RFC 7914 and mbedtls's own PBKDF2:
// what access control's password hash, tokens and cookies stand on.
#include "mbed_crypto.hpp"

#include <gtest/gtest.h>
#include <mbedtls/pkcs5.h>

#include <set>
#include <string>

#include "access/pbkdf2.hpp"
#include "util/hex.hpp"

namespace rotord::linux_port {
namespace {

using access::Pbkdf2;

std::string hex_of(std::span<const std::uint8_t> bytes) {
  std::string s(2 * bytes.size(), '?');
  hex::encode(bytes, s.data());
  return s;
}

TEST(MbedCrypto, HmacSha256MatchesRfc4231) {
  MbedCrypto crypto;
  ASSERT_TRUE(crypto.ready());
  access::Sha256Digest mac;
  const std::string key1(20, '\x0b');
  ASSERT_TRUE(crypto.hmac_sha256(access::bytes_of(key1), access::bytes_of("Hi There"), mac));
  EXPECT_EQ(hex_of(mac), "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
  ASSERT_TRUE(crypto.hmac_sha256(access::bytes_of("Jefe"),
                                 access::bytes_of("what do ya want for nothing?"), mac));
  EXPECT_EQ(hex_of(mac), "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
}

std::string pbkdf2_in_slices(MbedCrypto& crypto, std::string_view password, std::string_view salt,
                             std::uint32_t iterations, std::uint32_t slice) {
  Pbkdf2 job;
  job.start(password, access::bytes_of(salt), iterations);
  int slices = 0;
  while (job.step(crypto, slice) == Pbkdf2::Status::kRunning) ++slices;
  EXPECT_EQ(job.status(), Pbkdf2::Status::kDone);
  EXPECT_EQ(slices + 1, static_cast<int>((iterations + slice - 1) / slice));
  return hex_of(job.key());
}

TEST(MbedCrypto, SlicedPbkdf2MatchesRfc7914) {
  MbedCrypto crypto;
  EXPECT_EQ(pbkdf2_in_slices(crypto, "passwd", "salt", 1, 1),
            "55ac046e56e3089fec1691c22544b605f94185216dde0465e68b9d57c20dacbc");
  EXPECT_EQ(pbkdf2_in_slices(crypto, "Password", "NaCl", 80000, 777),
            "4ddcd8f60b98be21830cee5ef22701f9641a4418d04c0414aeff08876b34ab56");
}

TEST(MbedCrypto, SlicedPbkdf2MatchesMbedtlsOwnPbkdf2WhateverTheSlice) {
  MbedCrypto crypto;
  mbedtls_md_context_t md;
  mbedtls_md_init(&md);
  ASSERT_EQ(mbedtls_md_setup(&md, mbedtls_md_info_from_type(MBEDTLS_MD_SHA256), 1), 0);
  const std::string password = "correct horse battery staple";
  const std::string salt = "0123456789abcdef";
  for (std::uint32_t slice : {1u, 3u, 64u, 5000u}) {
    std::uint8_t expected[32];
    ASSERT_EQ(mbedtls_pkcs5_pbkdf2_hmac(
                  &md, reinterpret_cast<const unsigned char*>(password.data()), password.size(),
                  reinterpret_cast<const unsigned char*>(salt.data()), salt.size(), 1000,
                  sizeof expected, expected),
              0);
    EXPECT_EQ(pbkdf2_in_slices(crypto, password, salt, 1000, slice), hex_of(expected))
        << "slice " << slice;
  }
  mbedtls_md_free(&md);
}

TEST(MbedCrypto, Pbkdf2RefusesWhatItCannotHoldAndForgetsThePassword) {
  MbedCrypto crypto;
  Pbkdf2 job;
  job.start(std::string(65, 'x'), access::bytes_of("salt"), 10);
  EXPECT_EQ(job.status(), Pbkdf2::Status::kFailed);
  job.start("pw", access::bytes_of(std::string(33, 's')), 10);
  EXPECT_EQ(job.status(), Pbkdf2::Status::kFailed);
  job.start("pw", access::bytes_of("salt"), 0);
  EXPECT_EQ(job.status(), Pbkdf2::Status::kFailed);
  job.start("pw", access::bytes_of("salt"), 2);
  EXPECT_EQ(job.step(crypto, 100), Pbkdf2::Status::kDone);
  EXPECT_EQ(job.iterations_done(), 2u);
}

TEST(MbedCrypto, RandomBytesDoNotRepeat) {
  MbedCrypto crypto;
  std::set<std::string> seen;
  for (int n = 0; n < 1000; ++n) {
    std::array<std::uint8_t, 16> bytes{};
    ASSERT_TRUE(crypto.random(bytes));
    EXPECT_TRUE(seen.insert(hex_of(bytes)).second);
  }
  std::array<std::uint8_t, 4000> big{};  // more than one DRBG request
  EXPECT_TRUE(crypto.random(big));
}

TEST(MbedCrypto, EqualComparesWholeStringsOfTheSameLength) {
  MbedCrypto crypto;
  const std::uint8_t a[] = {1, 2, 3, 4};
  const std::uint8_t b[] = {1, 2, 3, 5};
  const std::uint8_t c[] = {1, 2, 3};
  EXPECT_TRUE(crypto.equal(a, a));
  EXPECT_FALSE(crypto.equal(a, b));
  EXPECT_FALSE(crypto.equal(a, c));
}

}  // namespace
}  // namespace rotord::linux_port
