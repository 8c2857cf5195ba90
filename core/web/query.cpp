#include "web/query.hpp"

#include "util/slice.hpp"

namespace rotord::web {
namespace {

int hex(char h) {
  return h >= '0' && h <= '9'   ? h - '0'
         : h >= 'a' && h <= 'f' ? h - 'a' + 10
         : h >= 'A' && h <= 'F' ? h - 'A' + 10
                                : -1;
}

}  // namespace

bool query_value(std::string_view query, std::string_view name, char* out, std::size_t capacity) {
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view pair = text::slice(query, 0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : text::slice(query, amp + 1);
    const std::size_t eq = pair.find('=');
    if (text::slice(pair, 0, eq) != name) continue;
    const std::string_view value =
        eq == std::string_view::npos ? std::string_view{} : text::slice(pair, eq + 1);
    std::size_t n = 0;
    for (std::size_t i = 0; i < value.size(); ++i) {
      char c = value[i];
      if (c == '+') {
        c = ' ';
      } else if (c == '%') {
        if (i + 2 >= value.size()) return false;
        const int hi = hex(value[i + 1]);
        const int lo = hex(value[i + 2]);
        if (hi < 0 || lo < 0) return false;
        c = static_cast<char>(hi * 16 + lo);
        i += 2;
      }
      if (n + 1 >= capacity) return false;
      out[n++] = c;
    }
    out[n] = '\0';
    return true;
  }
  return false;
}

}  // namespace rotord::web
