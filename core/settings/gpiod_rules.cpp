#include "settings/gpiod_rules.hpp"

#include <cstdio>
#include <cstring>

namespace rotord::settings {

bool is_gpiod_line(Id id) {
  const Def& d = def(id);
  return std::strncmp(d.key, "gpiod.", 6) == 0 && std::strcmp(d.unit, "line") == 0;
}

std::optional<Error> check_gpiod_lines(const Settings& s, char* detail, std::size_t capacity) {
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    if (!is_gpiod_line(id) || s.i(id) < 0) continue;
    for (std::size_t m = 0; m < n; ++m) {
      const auto other = static_cast<Id>(m);
      if (is_gpiod_line(other) && s.i(other) == s.i(id)) {
        std::snprintf(detail, capacity, "%s and %s both use line %d", def(other).key, def(id).key,
                      s.i(id));
        return Error::kOutOfRange;
      }
    }
  }
  return std::nullopt;
}

}  // namespace rotord::settings
