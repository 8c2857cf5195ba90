#include "access/api_token.hpp"

#include <cstdio>
#include <cstring>

#include "util/hex.hpp"
#include "util/slice.hpp"

namespace rotord::access {
namespace {

constexpr std::string_view kHashLabel = "rotord api token v1";

}  // namespace

const char* scope_name(Scope scope) {
  return scope == Scope::kControl ? "control" : "read";
}

bool valid_token_name(std::string_view name) {
  if (name.empty() || name.size() > TokenRecord::kMaxNameBytes) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_' || c == '.';
    if (!ok) return false;
  }
  return true;
}

bool parse_token_record(std::string_view text, TokenRecord& out) {
  const std::size_t first = text.find(':');
  if (first == std::string_view::npos) return false;
  const std::size_t second = text.find(':', first + 1);
  if (second == std::string_view::npos) return false;
  const std::string_view name = text::slice(text, 0, first);
  const std::string_view scope = text::slice(text, first + 1, second - first - 1);
  if (!valid_token_name(name)) return false;
  TokenRecord parsed;
  if (scope == "read") {
    parsed.scope = Scope::kRead;
  } else if (scope == "control") {
    parsed.scope = Scope::kControl;
  } else {
    return false;
  }
  if (!hex::decode(text::slice(text, second + 1), parsed.hash)) return false;
  std::memcpy(parsed.name, name.data(), name.size());
  parsed.name[name.size()] = '\0';
  out = parsed;
  return true;
}

std::size_t format_token_record(const TokenRecord& record, char* out, std::size_t capacity) {
  char hash[2 * TokenRecord::kHashBytes];
  hex::encode(record.hash, hash);
  const int n = std::snprintf(out, capacity, "%s:%s:%.*s", record.name, scope_name(record.scope),
                              static_cast<int>(sizeof hash), hash);
  if (n <= 0 || static_cast<std::size_t>(n) >= capacity) return 0;
  return static_cast<std::size_t>(n);
}

bool hash_token(Crypto& crypto, std::string_view token,
                std::array<std::uint8_t, TokenRecord::kHashBytes>& out) {
  Sha256Digest mac;
  if (!crypto.hmac_sha256(bytes_of(kHashLabel), bytes_of(token), mac)) return false;
  std::memcpy(out.data(), mac.data(), out.size());
  return true;
}

bool make_token(Crypto& crypto, char (&text)[kTokenTextBytes + 1],
                std::array<std::uint8_t, TokenRecord::kHashBytes>& hash) {
  std::array<std::uint8_t, kTokenRandomBytes> random{};
  if (!crypto.random(random)) return false;
  std::memcpy(text, kTokenPrefix.data(), kTokenPrefix.size());
  hex::encode(random, text + kTokenPrefix.size());
  text[kTokenTextBytes] = '\0';
  return hash_token(crypto, std::string_view(text, kTokenTextBytes), hash);
}

}  // namespace rotord::access
