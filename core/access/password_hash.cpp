#include "access/password_hash.hpp"

#include <cstdio>

#include "util/hex.hpp"
#include "util/slice.hpp"

namespace rotord::access {

bool parse_password_hash(std::string_view text, PasswordHash& out) {
  if (!text.starts_with(kPasswordHashPrefix)) return false;
  text.remove_prefix(kPasswordHashPrefix.size());
  const std::size_t dollar = text.find('$');
  if (dollar == 0 || dollar == std::string_view::npos || dollar > 8) return false;
  std::uint32_t iterations = 0;
  for (char c : text::slice(text, 0, dollar)) {
    if (c < '0' || c > '9') return false;
    iterations = iterations * 10 + static_cast<std::uint32_t>(c - '0');
  }
  if (text[0] == '0' || iterations < PasswordHash::kMinIterations ||
      iterations > PasswordHash::kMaxIterations)
    return false;
  text.remove_prefix(dollar + 1);
  constexpr std::size_t kSaltHex = 2 * PasswordHash::kSaltBytes;
  if (text.size() != kSaltHex + 1 + 2 * PasswordHash::kKeyBytes || text[kSaltHex] != '$')
    return false;
  PasswordHash parsed;
  parsed.iterations = iterations;
  if (!hex::decode(text::slice(text, 0, kSaltHex), parsed.salt) ||
      !hex::decode(text::slice(text, kSaltHex + 1), parsed.key))
    return false;
  out = parsed;
  return true;
}

std::size_t format_password_hash(const PasswordHash& hash, char* out, std::size_t capacity) {
  char salt[2 * PasswordHash::kSaltBytes];
  char key[2 * PasswordHash::kKeyBytes];
  hex::encode(hash.salt, salt);
  hex::encode(hash.key, key);
  const int n = std::snprintf(
      out, capacity, "%.*s%lu$%.*s$%.*s", static_cast<int>(kPasswordHashPrefix.size()),
      kPasswordHashPrefix.data(), static_cast<unsigned long>(hash.iterations),
      static_cast<int>(sizeof salt), salt, static_cast<int>(sizeof key), key);
  if (n <= 0 || static_cast<std::size_t>(n) >= capacity) return 0;
  return static_cast<std::size_t>(n);
}

const char* password_rule_violation(std::string_view password) {
  if (password.size() < 8) return "the password needs at least 8 characters";
  if (password.size() > 63) return "the password may have at most 63 characters";
  for (char c : password)
    if (c < 0x20 || c > 0x7e) return "only printable ASCII characters (space to ~) in a password";
  return nullptr;
}

}  // namespace rotord::access
