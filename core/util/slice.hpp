#pragma once
#include <algorithm>
#include <cstddef>
#include <string_view>

namespace rotord::text {

/// std::string_view::substr without its bounds check. substr throws
/// std::out_of_range when `pos` is past the end, and that call links
/// libstdc++'s exception runtime (__cxa_throw, the personality routine, the
/// unwinder: about 9 KB of flash and 4 KB of RAM on the RP2040) into the
/// firmware even though the core is built with -fno-exceptions; there a throw
/// would abort and reset the chip. The core uses this instead (the image check
/// in cmake/check-no-exceptions.cmake keeps it that way): a `pos` past the end
/// gives the empty view at the end, and `count` is clamped as substr clamps it.
constexpr std::string_view slice(std::string_view s, std::size_t pos,
                                 std::size_t count = std::string_view::npos) noexcept {
  pos = std::min(pos, s.size());
  return std::string_view(s.data() + pos, std::min(count, s.size() - pos));
}

}  // namespace rotord::text
