#pragma once
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <string_view>

#include "protocol/session.hpp"

namespace rotord::protocol {

/// How one line protocol ends a reply line, and the whole reply it sends
/// instead of one that does not fit its buffer.
struct ReplyRules {
  std::string_view line_end;  ///< "\r\n" or "\n"
  /// Sent instead of an overflowed reply, line end included: the protocol's
  /// own error, so a client that waits for an answer gets one.
  std::string_view overflow;
};

/// One reply of a line protocol, built in a fixed buffer and written with a
/// single ByteSink::write (Gpredict reads each reply with one recv). Every
/// line protocol (WRC, rotctld, GS-232, Easycomm, seed) uses this type, so
/// all share one overflow policy: once anything appended does not fit, the
/// whole reply becomes `rules.overflow`, never a truncated line and never
/// silence. The buffer lives wherever the caller puts it (the stack for a
/// short line, the session for rotctld's 1.5 KB dump_caps).
template <std::size_t Capacity>
class LineReply {
 public:
  static constexpr std::size_t kCapacity = Capacity;

  explicit LineReply(ReplyRules rules) : rules_(rules) {}

  void append(std::string_view text) {
    if (overflowed_ || text.size() > Capacity - length_) {
      overflowed_ = true;
      return;
    }
    for (char c : text) buf_[length_++] = c;
  }
  void put(char c) { append(std::string_view(&c, 1)); }
  /// printf-style. Without arguments the text is copied as it is (a '%' in
  /// it stays a '%').
  template <typename... Args>
  void format(const char* fmt, Args... args) {
    if (overflowed_) return;
    // snprintf needs room for its terminating NUL, which is not sent.
    char* const at = buf_ + length_;
    const std::size_t room = Capacity - length_;
    int n = 0;
    if constexpr (sizeof...(Args) == 0) {
      n = std::snprintf(at, room + 1, "%s", fmt);
    } else {
      n = std::snprintf(at, room + 1, fmt, args...);
    }
    if (n < 0 || static_cast<std::size_t>(n) > room) {
      overflowed_ = true;
      return;
    }
    length_ += static_cast<std::size_t>(n);
  }
  /// format() with a printf-style function's own arguments.
  void vformat(const char* fmt, std::va_list args) {
    if (overflowed_) return;
    const std::size_t room = Capacity - length_;
    const int n = std::vsnprintf(buf_ + length_, room + 1, fmt, args);
    if (n < 0 || static_cast<std::size_t>(n) > room) {
      overflowed_ = true;
      return;
    }
    length_ += static_cast<std::size_t>(n);
  }
  /// The protocol's line end.
  void end_line() { append(rules_.line_end); }

  bool overflowed() const { return overflowed_; }
  /// What goes to the client: the reply, or the overflow error.
  std::string_view view() const {
    return overflowed_ ? rules_.overflow : std::string_view(buf_, length_);
  }
  void clear() {
    length_ = 0;
    overflowed_ = false;
  }
  /// Writes the reply in one unit and starts a new one.
  void send(ByteSink& out) {
    out.write(view());
    clear();
  }
  /// One whole line: formatted, ended and sent.
  template <typename... Args>
  void line(ByteSink& out, const char* fmt, Args... args) {
    clear();
    format(fmt, args...);
    end_line();
    send(out);
  }
  /// A fixed line (never used as a format), e.g. one from a table.
  void text_line(ByteSink& out, std::string_view text) {
    clear();
    append(text);
    end_line();
    send(out);
  }

 private:
  ReplyRules rules_;
  // One more byte for snprintf's NUL.
  char buf_[Capacity + 1];
  std::size_t length_ = 0;
  bool overflowed_ = false;
};

}  // namespace rotord::protocol
