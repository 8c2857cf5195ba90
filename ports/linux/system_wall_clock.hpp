#pragma once
#include <sys/timex.h>

#include <chrono>

#include "hal/wall_clock.hpp"

namespace rotord::linux_port {

/// The host's system clock (kept by the host's NTP client) as the API's
/// calendar time; rotord does no SNTP of its own on Linux.
class SystemWallClock final : public hal::WallClock {
 public:
  std::optional<std::int64_t> unix_ms() const override {
    using namespace std::chrono;
    return duration_cast<milliseconds>(system_clock::now().time_since_epoch()).count();
  }
  /// The kernel's view (adjtimex, as timedatectl's "System clock
  /// synchronized"): an NTP client (chrony, systemd-timesyncd, ntpd) keeps it.
  bool synchronized() const override {
    struct timex tx {};
    const int state = ::adjtimex(&tx);
    return state != -1 && state != TIME_ERROR && (tx.status & STA_UNSYNC) == 0;
  }
};

/// The simulator's UTC under --speedup or --clock manual: the start's UTC
/// (--utc-start, or the system clock when rotord started) plus controller
/// time, so a simulated pass runs at the simulated rotator's pace.
class SimulatedUtcClock final : public hal::WallClock {
 public:
  SimulatedUtcClock(std::int64_t start_utc_ms, const std::int64_t* controller_ms)
      : start_(start_utc_ms), now_(controller_ms) {}
  std::optional<std::int64_t> unix_ms() const override { return start_ + *now_; }

 private:
  std::int64_t start_;
  const std::int64_t* now_;
};

}  // namespace rotord::linux_port
