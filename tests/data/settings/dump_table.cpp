// Prints every column of every settings row, one row a line, in table order:
// how main_table.txt was made from main before the per-axis rows were
// declared once (README.md). Not built by CMake: compile it against a
// tree's core and its built libraries. Only the public settings API.
#include <cstdio>
#include <string>

#include "settings/settings.hpp"

int main() {
  using namespace rotord::settings;
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    const Def& d = def(id);
    const std::string when(condition(id));
    std::printf(
        "%s|type=%d|flags=%d|unit=%s|min=%.17g|max=%.17g|default=%.17g|group=%s|choices=%s|"
        "label=%s|when=%s\n",
        d.key, static_cast<int>(d.type), static_cast<int>(d.flags), d.unit, d.min, d.max,
        d.default_value, d.group, d.choices, d.label, when.c_str());
  }
}
