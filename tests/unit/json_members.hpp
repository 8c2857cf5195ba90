#pragma once
// The members of a JSON object or the elements of an array as their text,
// and whether one document's members appear in another's unchanged and in
// the same order: the settings of main (tests/data/settings/) must read the
// same byte for byte, while a setting added since may sit between them.
// Plain string scanning, for the M0+ as for the host.
#include <string>
#include <string_view>
#include <vector>

namespace rotord::testing {

/// The texts between the top-level commas of the object or array that
/// starts at `json`'s first '{' or '[' (strings and nesting respected).
inline std::vector<std::string_view> json_members(std::string_view json) {
  std::vector<std::string_view> members;
  const std::size_t open = json.find_first_of("{[");
  if (open == std::string_view::npos) return members;
  int depth = 0;
  bool in_string = false;
  std::size_t start = open + 1;
  for (std::size_t n = open; n < json.size(); ++n) {
    const char c = json[n];
    if (in_string) {
      if (c == '\\')
        ++n;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      ++depth;
    } else if (c == '}' || c == ']' || (c == ',' && depth == 1)) {
      if (c != ',' && --depth > 0) continue;
      if (n > start) members.push_back(json.substr(start, n - start));
      start = n + 1;
      if (c != ',') break;
    }
  }
  return members;
}

/// The text of the value of member `key` of the object `json` ("" when none).
inline std::string_view json_member_value(std::string_view json, std::string_view key) {
  for (std::string_view member : json_members(json)) {
    const std::size_t colon = member.find(':');
    if (colon != std::string_view::npos && member.substr(0, colon) == key)
      return member.substr(colon + 1);
  }
  return {};
}

/// "" when every member of `before` is among the members of `now`, unchanged
/// and in the same order (members added in between allowed); else the first
/// member of `before` that is not.
inline std::string missing_or_changed(std::string_view before, std::string_view now) {
  const std::vector<std::string_view> old_members = json_members(before);
  const std::vector<std::string_view> new_members = json_members(now);
  std::size_t at = 0;
  for (std::string_view member : old_members) {
    while (at < new_members.size() && new_members[at] != member) ++at;
    if (at == new_members.size()) return std::string(member);
    ++at;
  }
  return old_members.empty() ? "(no members)" : "";
}

}  // namespace rotord::testing
