#pragma once
// The web password as stored (the web.password setting): never the password,
// its PBKDF2-HMAC-SHA256 over a random salt, with the iteration count it was
// made with, as text:
//
//   pbkdf2-sha256$<iterations>$<salt, 32 hex>$<derived key, 32 hex>
//
// 16 bytes of salt and of derived key (PBKDF2's dkLen = 16: one block, cut);
// short enough for the settings document's 96-byte strings. A hash made on
// one port verifies on the other: the count travels with it.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rotord::access {

struct PasswordHash {
  static constexpr std::size_t kSaltBytes = 16;
  static constexpr std::size_t kKeyBytes = 16;
  /// Accepted when read back; the ports make theirs with their own count
  /// (ApiContext::pbkdf2_iterations).
  static constexpr std::uint32_t kMinIterations = 1000;
  static constexpr std::uint32_t kMaxIterations = 10'000'000;
  /// The longest text form, without a NUL.
  static constexpr std::size_t kMaxTextBytes = 14 + 8 + 1 + 2 * kSaltBytes + 1 + 2 * kKeyBytes;

  std::uint32_t iterations = 0;
  std::array<std::uint8_t, kSaltBytes> salt{};
  std::array<std::uint8_t, kKeyBytes> key{};
};

inline constexpr std::string_view kPasswordHashPrefix = "pbkdf2-sha256$";

/// Reads the text form; false for anything else (a count outside the limits included).
bool parse_password_hash(std::string_view text, PasswordHash& out);

/// Writes the text form and a NUL; returns its length, 0 when `capacity` is short.
std::size_t format_password_hash(const PasswordHash& hash, char* out, std::size_t capacity);

/// What a new web password must be: 8 to 63 printable ASCII characters (a
/// phone keyboard types them all). Null when fine, else the reason.
const char* password_rule_violation(std::string_view password);

}  // namespace rotord::access
