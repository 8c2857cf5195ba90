#include "metrics/registry.hpp"

#include "protocol/protocol_registry.hpp"

namespace rotord::metrics {

const char* protocol_label(Protocol protocol) {
  if (protocol == Protocol::kHttp) return "http";
  // A line protocol's label is its registry key (a literal, NUL-terminated).
  const protocol::ProtocolInfo* row = protocol::find_protocol(protocol);
  return row != nullptr ? row->key.data() : "?";
}

namespace {

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.starts_with(prefix);
}

/// "HTTP/1.1 404 ..." and up: a status line of 400 or more.
bool is_http_error(std::string_view reply) {
  constexpr std::string_view kVersion = "HTTP/1.1 ";
  if (!starts_with(reply, kVersion) || reply.size() < kVersion.size() + 3) return false;
  const char first = reply[kVersion.size()];
  return first >= '4' && first <= '5';
}

}  // namespace

bool is_error_reply(Protocol protocol, std::string_view reply) {
  if (protocol == Protocol::kHttp) return is_http_error(reply);
  const protocol::ProtocolInfo* row = protocol::find_protocol(protocol);
  return row != nullptr && row->is_error_reply(reply);
}

}  // namespace rotord::metrics
