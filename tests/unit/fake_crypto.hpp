#pragma once
// access::Crypto for the core's unit tests, which also run on the Cortex-M0+
// under qemu where no mbedtls is built. NOT cryptography: "random" bytes
// from a counter, a keyed mixing function in place of HMAC. It keeps what
// the logic relies on (deterministic, different inputs give different
// digests, lengths as the real ones); the real implementations are tested
// against published vectors in tests/linux/mbed_crypto_test.cpp.
#include <cstring>

#include "access/crypto.hpp"

namespace rotord::testing {

class FakeCrypto final : public access::Crypto {
 public:
  bool random_works = true;
  int hmac_calls = 0;

  bool random(std::span<std::uint8_t> out) override {
    if (!random_works) return false;
    for (std::uint8_t& b : out) {
      state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
      b = static_cast<std::uint8_t>(state_ >> 56);
    }
    return true;
  }

  bool hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message,
                   access::Sha256Digest& out) override {
    ++hmac_calls;
    // FNV-1a over key, a separator and message, stretched to 32 bytes.
    std::uint64_t h = 1469598103934665603ULL;
    auto mix = [&h](std::uint8_t b) {
      h ^= b;
      h *= 1099511628211ULL;
    };
    for (std::uint8_t b : key) mix(b);
    mix(0xA5);
    mix(static_cast<std::uint8_t>(key.size()));
    for (std::uint8_t b : message) mix(b);
    for (std::size_t n = 0; n < out.size(); ++n) {
      mix(static_cast<std::uint8_t>(n));
      out[n] = static_cast<std::uint8_t>(h >> 32);
    }
    return true;
  }

  bool equal(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) const override {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size()) == 0;
  }

 private:
  std::uint64_t state_ = 42;
};

}  // namespace rotord::testing
