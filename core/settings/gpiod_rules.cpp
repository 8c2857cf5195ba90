#include "settings/gpiod_rules.hpp"

#include <cstdio>
#include <cstring>

namespace rotord::settings {
namespace {

bool has(Id id, const char* prefix, const char* unit) {
  const Def& d = def(id);
  return std::strncmp(d.key, prefix, std::strlen(prefix)) == 0 && std::strcmp(d.unit, unit) == 0;
}

/// The first two rows of one kind (prefix and unit) that hold the same
/// non-negative number.
std::optional<Error> check_distinct(const Settings& s, const char* prefix, const char* unit,
                                    const char* noun, char* detail, std::size_t capacity) {
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    if (!has(id, prefix, unit) || s.i(id) < 0) continue;
    for (std::size_t m = 0; m < n; ++m) {
      const auto other = static_cast<Id>(m);
      if (has(other, prefix, unit) && s.i(other) == s.i(id)) {
        std::snprintf(detail, capacity, "%s and %s both use %s %d", def(other).key, def(id).key,
                      noun, s.i(id));
        return Error::kOutOfRange;
      }
    }
  }
  return std::nullopt;
}

}  // namespace

bool is_gpiod_line(Id id) {
  return has(id, "gpiod.", "line");
}

std::optional<Error> check_gpiod_lines(const Settings& s, char* detail, std::size_t capacity) {
  if (const auto e = check_distinct(s, "gpiod.", "line", "line", detail, capacity)) return e;
  return check_distinct(s, "pwm.", "channel", "PWM channel", detail, capacity);
}

}  // namespace rotord::settings
