#pragma once
#include <cstdint>

namespace rotord {

/// Which way an axis turns, shared by every layer that asks for or reports a
/// move (buttons, protocols, the axis and its relay sequences).
enum class Direction : std::int8_t { kCcw = -1, kNone = 0, kCw = 1 };  // el: kCcw = down

}  // namespace rotord
