#pragma once
// How the console's files (console_*.cpp) write a reply line: one helper
// for all of them, so each command's file holds only its commands.
#include <algorithm>
#include <cstddef>
#include <string_view>

#include "protocol/console_session.hpp"
#include "settings/settings.hpp"

namespace rotord::protocol::console {

/// One reply line, printf-style (console_reply.cpp: one copy for every
/// console file, where each kept its own instances of the template).
void send_line(ByteSink& out, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

/// One reply line; without arguments the text is sent as it is (a '%' in
/// it stays a '%').
template <typename... Args>
void send(ByteSink& out, const char* fmt, Args... args) {
  if constexpr (sizeof...(Args) == 0) {
    send_line(out, "%s", fmt);
  } else {
    send_line(out, fmt, args...);
  }
}

inline void error(ByteSink& out, const char* reason) {
  send(out, "error: %s", reason);
}

/// The refusal of a command that changes something to a read-only client.
inline constexpr const char* kNotInControl =
    "read-only: this client may not change anything (access.serial_control, "
    "access.control_networks, or the web's control lock)";

/// Up to 32 characters of what the client typed, for an error reply: bytes
/// outside printable ASCII become '?', so garbage cannot upset a terminal.
struct Echo {
  explicit Echo(std::string_view s) {
    const std::size_t n = std::min(s.size(), sizeof text - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = static_cast<unsigned char>(s[i]);
      text[i] = c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
    }
    text[n] = '\0';
  }
  char text[33];
};

/// Formats one setting for a reply: "key=value" (secrets masked).
struct Value {
  Value(const settings::Settings& s, settings::Id id) { s.format_value(id, text, sizeof text); }
  char text[settings::kValueTextCapacity];
};

}  // namespace rotord::protocol::console
