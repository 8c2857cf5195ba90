#include "util/text.hpp"

#include <cmath>
#include <cstdlib>

#include "util/slice.hpp"

namespace rotord::text {
namespace {
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
char lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}
}  // namespace

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

bool parse_double(std::string_view s, double& out) {
  // Validate the shape first so strtod never sees hex, inf or nan.
  constexpr std::size_t kMaxChars = 48;
  if (s.empty() || s.size() > kMaxChars) return false;
  char buf[kMaxChars + 1];
  std::size_t n = 0;
  std::size_t i = 0;
  if (s[i] == '+' || s[i] == '-') buf[n++] = s[i++];
  bool digits = false;
  bool point = false;
  for (; i < s.size(); ++i) {
    char c = s[i];
    if (is_digit(c)) {
      digits = true;
      buf[n++] = c;
    } else if ((c == '.' || c == ',') && !point) {
      point = true;
      buf[n++] = '.';
    } else {
      break;
    }
  }
  if (!digits) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    buf[n++] = 'e';
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) buf[n++] = s[i++];
    bool exp_digits = false;
    for (; i < s.size() && is_digit(s[i]); ++i) {
      exp_digits = true;
      buf[n++] = s[i];
    }
    if (!exp_digits) return false;
  }
  if (i != s.size()) return false;
  buf[n] = '\0';
  double value = std::strtod(buf, nullptr);
  if (!std::isfinite(value)) return false;
  out = value;
  return true;
}

bool parse_int(std::string_view s, long& out) {
  if (s.empty() || s.size() > 10) return false;
  std::size_t i = 0;
  bool negative = false;
  if (s[0] == '+' || s[0] == '-') {
    negative = s[0] == '-';
    i = 1;
  }
  if (i == s.size()) return false;
  long value = 0;
  for (; i < s.size(); ++i) {
    if (!is_digit(s[i])) return false;
    value = value * 10 + (s[i] - '0');
  }
  out = negative ? -value : value;
  return true;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (lower(a[i]) != lower(b[i])) return false;
  return true;
}

std::string_view next_token(std::string_view& rest) {
  while (!rest.empty() && is_space(rest.front())) rest.remove_prefix(1);
  std::size_t end = 0;
  while (end < rest.size() && !is_space(rest[end])) ++end;
  std::string_view token = text::slice(rest, 0, end);
  rest.remove_prefix(end);
  return token;
}

}  // namespace rotord::text
