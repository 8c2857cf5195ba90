#pragma once
#include <cstdint>

namespace rotord {

/// Monotonic time in milliseconds. Always injected (Controller::tick(now)),
/// never read from the OS inside the core, so simulations run in virtual time.
using Millis = std::int64_t;

}  // namespace rotord
