#pragma once
#include <cstddef>
#include <string_view>

namespace rotord::web {

/// The value of `name` in a query string, percent-decoded into `out`
/// (NUL-terminated); false when absent or too long.
bool query_value(std::string_view query, std::string_view name, char* out, std::size_t capacity);

}  // namespace rotord::web
