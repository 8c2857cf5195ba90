#pragma once
#include <cstdint>
#include <optional>

namespace rotord::hal {

/// Calendar time (UTC) for reports, never for control: the control tick runs
/// on the monotonic Millis it is given. Linux reads the system clock; the
/// Pico W knows the time only once SNTP has answered.
class WallClock {
 public:
  virtual ~WallClock() = default;
  /// Milliseconds since 1970-01-01T00:00:00Z, or nullopt while unknown.
  virtual std::optional<std::int64_t> unix_ms() const = 0;
  /// Whether the time may be trusted for tracking (Linux: the kernel says
  /// NTP keeps it synchronized). A clock that knows the time only once it
  /// was set (SNTP) answers true.
  virtual bool synchronized() const { return true; }
};

}  // namespace rotord::hal
