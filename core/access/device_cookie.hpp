#pragma once
// A device cookie (OWASP, "Slow down online guessing attacks with device
// cookies"): a browser that has logged in before shows it, and its logins
// are not held back by the lock-out that strangers' guesses cause. The
// value is a random nonce and its HMAC-SHA256 under a key derived from the
// stored password hash, so it cannot be forged, survives a restart and dies
// with a new password. No state on the controller.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/crypto.hpp"
#include "access/password_hash.hpp"

namespace rotord::access {

class DeviceCookie {
 public:
  static constexpr std::string_view kCookieName = "rotord_device";
  static constexpr std::size_t kNonceBytes = 16;
  static constexpr std::size_t kTagBytes = 16;  ///< the HMAC, cut: 128 bits
  /// The value's length in hex.
  static constexpr std::size_t kTextBytes = 2 * (kNonceBytes + kTagBytes);
  /// A year: a browser used now and then is still recognised.
  static constexpr long kMaxAgeSeconds = 365L * 24 * 3600;

  /// A new value for `stored` (the password hash in force) into `out`
  /// (kTextBytes + 1 with the NUL); false when the crypto fails.
  static bool make(Crypto& crypto, const PasswordHash& stored, char (&out)[kTextBytes + 1]);
  /// Whether the Cookie header holds a value made for `stored`.
  static bool valid(Crypto& crypto, const PasswordHash& stored, std::string_view cookie_header);
};

}  // namespace rotord::access
