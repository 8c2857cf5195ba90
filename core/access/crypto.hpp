#pragma once
// The cryptography access control needs, behind one small interface with one
// implementation per port over a vetted library: Debian's mbedtls 2.28 on
// Linux (ports/linux/mbed_crypto.cpp), the pico-sdk's mbedtls 3.x on the
// Pico W (ports/pico_w/pico_crypto.cpp). Nothing here is hand-written
// cryptography; the core only composes these primitives (PBKDF2's loop in
// pbkdf2.hpp, checked against RFC 7914's vectors and mbedtls's own PBKDF2).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace rotord::access {

inline constexpr std::size_t kSha256Bytes = 32;
using Sha256Digest = std::array<std::uint8_t, kSha256Bytes>;

class Crypto {
 public:
  virtual ~Crypto() = default;

  /// Fills `out` from the port's cryptographically secure generator (a
  /// DRBG seeded from the OS or the hardware). False when it cannot: the
  /// caller must then refuse what needed the bytes, never fall back.
  virtual bool random(std::span<std::uint8_t> out) = 0;

  /// HMAC-SHA256 (RFC 2104) of `message` under `key`. False on a library
  /// error; `out` is then unspecified.
  virtual bool hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message,
                           Sha256Digest& out) = 0;

  /// Whether two byte strings of the same length are equal, in a time that
  /// does not depend on where they differ (a cookie, a token or a password
  /// hash compared byte by byte would leak how much of a guess was right).
  virtual bool equal(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) const = 0;
};

/// The bytes of a text, for the interface above.
inline std::span<const std::uint8_t> bytes_of(std::string_view text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

}  // namespace rotord::access
