#include "access/device_cookie.hpp"

#include <algorithm>
#include <cstring>

#include "access/web_sessions.hpp"
#include "util/hex.hpp"

namespace rotord::access {
namespace {

/// HMAC-SHA256("rotord device " + nonce) under the stored hash's secret key:
/// only the controller, which holds that key, can make one.
bool tag_of(Crypto& crypto, const PasswordHash& stored,
            const std::array<std::uint8_t, DeviceCookie::kNonceBytes>& nonce, Sha256Digest& tag) {
  constexpr std::string_view kLabel = "rotord device ";
  std::array<std::uint8_t, kLabel.size() + DeviceCookie::kNonceBytes> message{};
  std::memcpy(message.data(), kLabel.data(), kLabel.size());
  std::copy(nonce.begin(), nonce.end(), message.begin() + kLabel.size());
  return crypto.hmac_sha256(stored.key, message, tag);
}

}  // namespace

bool DeviceCookie::make(Crypto& crypto, const PasswordHash& stored, char (&out)[kTextBytes + 1]) {
  std::array<std::uint8_t, kNonceBytes + kTagBytes> value{};
  std::array<std::uint8_t, kNonceBytes> nonce{};
  Sha256Digest tag{};
  if (!crypto.random(nonce) || !tag_of(crypto, stored, nonce, tag)) return false;
  std::copy(nonce.begin(), nonce.end(), value.begin());
  std::copy(tag.begin(), tag.begin() + kTagBytes, value.begin() + kNonceBytes);
  hex::encode(value, out);
  out[kTextBytes] = '\0';
  return true;
}

bool DeviceCookie::valid(Crypto& crypto, const PasswordHash& stored,
                         std::string_view cookie_header) {
  std::array<std::uint8_t, kNonceBytes + kTagBytes> value{};
  if (!hex::decode(cookie_value(cookie_header, kCookieName), value)) return false;
  std::array<std::uint8_t, kNonceBytes> nonce{};
  std::copy(value.begin(), value.begin() + kNonceBytes, nonce.begin());
  Sha256Digest tag{};
  if (!tag_of(crypto, stored, nonce, tag)) return false;
  return crypto.equal(std::span<const std::uint8_t>(tag.data(), kTagBytes),
                      std::span<const std::uint8_t>(value.data() + kNonceBytes, kTagBytes));
}

}  // namespace rotord::access
