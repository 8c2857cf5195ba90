#pragma once
// The words of an Easycomm line: its separators, its tokens and the shape of
// a velocity field. Kept apart from the session so that easycomm_session.cpp
// holds the commands only.

#include <string_view>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol::easycomm {

/// A velocity field: exactly four digits, 0000..9999 mdeg/s. Hamlib's 204
/// backend, the one client that sends velocities, writes them "%04d"
/// (rotators/easycomm/easycomm.c, easycomm_rot_move_velocity), and its speed
/// level is 0..9999; "VU999", "VD-0" or "VL+0100" are typos or another
/// program's guess and are refused (ALSYNTAX) rather than read leniently.
inline bool is_velocity(std::string_view value) {
  if (value.size() != 4) return false;
  for (char c : value) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

inline bool is_separator(char c) {
  // ';' because Hamlib 4.5.4 sends "GS\n;" and the ';' opens the next line.
  return c == ' ' || c == '\t' || c == ';';
}

inline std::string_view next_token(std::string_view& rest) {
  std::size_t i = 0;
  while (i < rest.size() && is_separator(rest[i])) ++i;
  std::size_t j = i;
  while (j < rest.size() && !is_separator(rest[j])) ++j;
  const std::string_view token = text::slice(rest, i, j - i);
  rest.remove_prefix(j);
  return token;
}

inline bool starts_with(std::string_view token, std::string_view prefix) {
  return token.size() >= prefix.size() &&
         text::iequals(text::slice(token, 0, prefix.size()), prefix);
}

inline bool all_letters(std::string_view s) {
  for (char c : s) {
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) return false;
  }
  return !s.empty();
}

}  // namespace rotord::protocol::easycomm
