#pragma once
#include <cstddef>

namespace rotord::hal {

/// How the calendar clock is kept, in words for the owner: the set-up page's
/// station step (GET /api/setup "clock"). Linux: the kernel's NTP state
/// (what timedatectl shows); the Pico W: its SNTP client. Tracking points
/// from this clock, so an owner must see at once whether it can be trusted.
class ClockSync {
 public:
  virtual ~ClockSync() = default;
  /// One or two sentences into `out` (NUL-terminated, cut to `capacity`);
  /// returns the length written.
  virtual std::size_t describe(char* out, std::size_t capacity) const = 0;
};

}  // namespace rotord::hal
