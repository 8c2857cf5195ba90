#pragma once
// Web login sessions, in RAM: a random 128-bit id in the rotord_session
// cookie (HttpOnly, SameSite=Strict), an expiry, and whether the session
// logged in (an anonymous one only names who holds the control lock while
// access control is off). A restart logs everyone out.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/crypto.hpp"
#include "util/time.hpp"

namespace rotord::access {

class WebSessions {
 public:
  /// Browsers at once; the oldest session makes room for a new one.
  static constexpr std::size_t kMax = 8;
  static constexpr std::size_t kIdBytes = 16;
  static constexpr std::size_t kIdTextBytes = 2 * kIdBytes;
  static constexpr std::string_view kCookieName = "rotord_session";
  using Id = std::array<std::uint8_t, kIdBytes>;

  struct Entry {
    bool used = false;
    bool authenticated = false;
    Id id{};
    Millis created = 0;
    Millis expires = 0;
  };

  /// A new session; -1 when the port has no random bytes.
  int create(Crypto& crypto, Millis now, Millis lifetime_ms, bool authenticated);
  /// The live session a Cookie header names, or -1.
  int find(Crypto& crypto, std::string_view cookie_header, Millis now) const;
  void remove(int index);
  void remove_all();
  void expire(Millis now);

  const Entry& at(int index) const { return entries_[static_cast<std::size_t>(index)]; }
  /// The cookie's value (kIdTextBytes hex digits and a NUL).
  void id_text(int index, char (&out)[kIdTextBytes + 1]) const;

 private:
  std::array<Entry, kMax> entries_{};
};

/// The value of cookie `name` in a Cookie header ("a=1; rotord_session=..."),
/// or empty. Only the first cookie of that name counts.
std::string_view cookie_value(std::string_view cookie_header, std::string_view name);

}  // namespace rotord::access
