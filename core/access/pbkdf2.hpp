#pragma once
// PBKDF2-HMAC-SHA256 (RFC 8018 5.2) computed in slices: the web password's
// slow hash must not hold up the control tick or the Pico's watchdog, so
// the port runs a few iterations per pass of its loop (web_auth.hpp). Only
// the loop is here; each HMAC is the port's vetted implementation
// (crypto.hpp). Tested against RFC 7914's PBKDF2-HMAC-SHA256 vectors and
// against mbedtls_pkcs5_pbkdf2_hmac (tests/linux/mbed_crypto_test.cpp).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "access/crypto.hpp"

namespace rotord::access {

class Pbkdf2 {
 public:
  static constexpr std::size_t kMaxPasswordBytes = 64;
  static constexpr std::size_t kMaxSaltBytes = 32;

  enum class Status : std::uint8_t { kIdle, kRunning, kDone, kFailed };

  /// Begins deriving the first block (dkLen <= 32) of PBKDF2 over `password`
  /// and `salt`. A password or salt over the limits fails at once (kFailed).
  void start(std::string_view password, std::span<const std::uint8_t> salt,
             std::uint32_t iterations);

  /// Runs at most `max_iterations` HMAC iterations (at least one).
  Status step(Crypto& crypto, std::uint32_t max_iterations);

  Status status() const { return status_; }
  /// kDone: the derived key (its first bytes are a shorter dkLen's key).
  const Sha256Digest& key() const { return t_; }
  std::uint32_t iterations_done() const { return done_; }
  /// Forgets the password and the intermediate values.
  void clear();

 private:
  std::uint8_t password_[kMaxPasswordBytes] = {};
  std::size_t password_bytes_ = 0;
  std::uint8_t salt_block_[kMaxSaltBytes + 4] = {};  ///< salt || INT(1)
  std::size_t salt_block_bytes_ = 0;
  Sha256Digest u_{};
  Sha256Digest t_{};
  std::uint32_t done_ = 0;
  std::uint32_t iterations_ = 0;
  Status status_ = Status::kIdle;
};

}  // namespace rotord::access
