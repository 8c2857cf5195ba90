#pragma once
// The members of a small object body, each asked for by name and type: the
// command layer's arguments (command/json_args.hpp) and the access-control
// endpoints' bodies (web/auth_body.hpp) are read by this one loop, so an
// unknown member or a member of the wrong type is refused alike everywhere.
#include <cstddef>
#include <span>
#include <string_view>

#include "json/json_reader.hpp"

namespace rotord::web {

/// One member a body may hold.
struct JsonMember {
  /// A string goes to `text_buffer` (a password's 64 bytes), or without one
  /// to the member's own few bytes (the commands' axis, dir, mode names).
  JsonMember(const char* member_name, JsonType member_type, std::span<char> text_buffer = {})
      : name(member_name), type(member_type), text_buffer_(text_buffer) {}
  const char* name;
  JsonType type;
  bool present = false;
  /// A string longer than its buffer holds (less the NUL): read as "".
  bool too_long = false;
  /// Its value; a string's text copied and NUL-terminated (the reader's
  /// scratch is reused for the next member).
  JsonValue value;

 private:
  friend bool read_members(std::string_view, std::span<JsonMember>, char*, std::size_t);
  std::span<char> text_buffer_;
  char short_text_[16] = {};
};

/// Reads `body` (empty = {}) into `members`; false with `why` (a sentence:
/// "invalid JSON: ... (byte N)", "unknown member 'x'", "az must be a
/// number") on bad JSON, a member not asked for or one of the wrong type.
bool read_members(std::string_view body, std::span<JsonMember> members, char* why,
                  std::size_t why_bytes);

}  // namespace rotord::web
