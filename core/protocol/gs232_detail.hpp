#pragma once
// What gs232_session.cpp (the dispatch, the pages) and gs232_handlers.cpp
// (what each command does) share: the letters, the angle fields, one reply.
#include <string_view>

#include "protocol/gs232_session.hpp"

namespace rotord::protocol::gs232::detail {

inline char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

/// One angle or interval field: one to three decimal digits. The manual asks
/// for exactly three (zero-padded); fewer are accepted because nothing is
/// ambiguous about them. Signs, decimals and longer numbers are errors.
inline bool parse_field(std::string_view s, int& value) {
  if (s.empty() || s.size() > 3) return false;
  int v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  value = v;
  return true;
}

/// Formats a data reply (which always ends in CR LF) and sends it in one write.
/// A reply that cannot fit goes out as the protocol's error, never as silence.
template <typename... Args>
inline void send(ByteSink& out, const char* fmt, Args... args) {
  Gs232Session::Reply reply(Gs232Session::kReplyRules);
  reply.format(fmt, args...);
  reply.send(out);
}

}  // namespace rotord::protocol::gs232::detail
