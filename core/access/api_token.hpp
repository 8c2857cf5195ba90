#pragma once
// REST bearer tokens (Authorization: Bearer rtd_...). A token is 16 random
// bytes shown once, when it is made; only its hash is stored, in one of the
// web.token_N settings, as text:
//
//   <name>:<read|control>:<HMAC-SHA256 of the token, first 16 bytes, 32 hex>
//
// Tokens are random, so one keyed hash is enough (no slow hash: nothing to
// guess from a dictionary); HMAC under a fixed label keeps these hashes apart
// from any other SHA-256 use.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/crypto.hpp"

namespace rotord::access {

/// What a token allows. kRead: every GET (and STOP, which needs nothing);
/// kControl: also commands and settings other than secrets and access rules.
enum class Scope : std::uint8_t { kRead, kControl };

const char* scope_name(Scope scope);

struct TokenRecord {
  static constexpr std::size_t kMaxNameBytes = 16;
  static constexpr std::size_t kHashBytes = 16;
  char name[kMaxNameBytes + 1] = {};
  Scope scope = Scope::kRead;
  std::array<std::uint8_t, kHashBytes> hash{};
};

inline constexpr std::string_view kTokenPrefix = "rtd_";
inline constexpr std::size_t kTokenRandomBytes = 16;
/// "rtd_" and 32 hex digits.
inline constexpr std::size_t kTokenTextBytes = kTokenPrefix.size() + 2 * kTokenRandomBytes;

/// A token's name: 1 to 16 of a-z, A-Z, 0-9, '-', '_', '.'.
bool valid_token_name(std::string_view name);

bool parse_token_record(std::string_view text, TokenRecord& out);
/// Writes the text form and a NUL; returns its length, 0 when `capacity` is short.
std::size_t format_token_record(const TokenRecord& record, char* out, std::size_t capacity);

/// The stored hash of a presented token's text. False on a crypto error.
bool hash_token(Crypto& crypto, std::string_view token,
                std::array<std::uint8_t, TokenRecord::kHashBytes>& out);

/// Makes a new token: its text (kTokenTextBytes characters and a NUL in
/// `text`) and its hash. False when the port has no random bytes.
bool make_token(Crypto& crypto, char (&text)[kTokenTextBytes + 1],
                std::array<std::uint8_t, TokenRecord::kHashBytes>& hash);

}  // namespace rotord::access
