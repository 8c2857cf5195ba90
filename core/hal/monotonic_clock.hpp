#pragma once
#include <cstdint>

namespace rotord::hal {

/// The port's monotonic clock, for reports about the loop itself (GET
/// /healthz: how long ago the control tick last ran). The control tick is
/// still given its time; this is never read inside it.
class MonotonicClock {
 public:
  virtual ~MonotonicClock() = default;
  /// Microseconds since an arbitrary start, never going back.
  virtual std::int64_t now_us() const = 0;
};

}  // namespace rotord::hal
