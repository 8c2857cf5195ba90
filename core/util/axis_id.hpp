#pragma once
#include <cstdint>

namespace rotord {

enum class AxisId : std::uint8_t { kAz = 0, kEl = 1 };

inline constexpr int kMaxAxes = 2;

inline constexpr int axis_index(AxisId id) {
  return static_cast<int>(id);
}

}  // namespace rotord
