#include "protocol/rotctld_number.hpp"

#include <array>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol::rotctld {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

/// Length of the longest prefix of `s` that is [+-]digits[.digits][e[+-]digits]
/// with at least one mantissa digit; 0 when there is none.
std::size_t number_prefix(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  bool digits = false;
  while (i < s.size() && is_digit(s[i])) ++i, digits = true;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i, digits = true;
  }
  if (!digits) return 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    if (j < s.size() && is_digit(s[j])) {
      while (j < s.size() && is_digit(s[j])) ++j;
      i = j;
    }
  }
  return i;
}

}  // namespace

bool scan_float(std::string_view token, double& out, bool comma_is_point) {
  constexpr std::size_t kMaxChars = 48;
  std::array<char, kMaxChars> buf{};
  const std::size_t n = token.size() < kMaxChars ? token.size() : kMaxChars;
  bool comma_done = !comma_is_point;
  for (std::size_t i = 0; i < n; ++i) {
    char c = token[i];
    if (c == ',' && !comma_done) {
      c = '.';
      comma_done = true;
    }
    buf[i] = c;
  }
  const std::string_view text(buf.data(), n);
  const std::size_t len = number_prefix(text);
  if (len == 0) return false;
  // "0x1A" would be 26 to sscanf; refuse it rather than read it as 0.
  if (len < n && (text[len] == 'x' || text[len] == 'X')) return false;
  return text::parse_double(text::slice(text, 0, len), out);
}

bool scan_int(std::string_view token, long& out) {
  std::size_t i = 0;
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
  const std::size_t first_digit = i;
  while (i < token.size() && is_digit(token[i])) ++i;
  if (i == first_digit || i - first_digit > 9) return false;
  return text::parse_int(text::slice(token, 0, i), out);
}

bool scan_whole_int(std::string_view token, long& out) {
  std::size_t i = 0;
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
  for (std::size_t j = i; j < token.size(); ++j) {
    if (!is_digit(token[j])) return false;
  }
  return scan_int(token, out);
}

}  // namespace rotord::protocol::rotctld
