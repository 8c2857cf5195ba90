#pragma once
// Calendar time on the Pico W: lwIP's SNTP client (apps/sntp) calls the
// SNTP_SET_SYSTEM_TIME_US hook of config/lwipopts.h, which lands in
// on_sntp_time(); the time is kept as an offset to the monotonic clock
// (TimeBase), so no RTC or AON timer is needed and a time step never
// disturbs the control tick. No SDK here: the host tests call the same code.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hal/clock_sync.hpp"
#include "hal/wall_clock.hpp"
#include "util/utc_time.hpp"

namespace rotord::pico_w {

/// The SNTP answer (seconds since 1970, microseconds) received at monotonic
/// time `now`.
void on_sntp_time(std::uint32_t sec, std::uint32_t us, Millis now);

/// GET /api/status time_utc: unknown until the first SNTP answer.
class SntpWallClock final : public hal::WallClock {
 public:
  using NowFn = Millis (*)();
  explicit SntpWallClock(NowFn now) : now_(now) {}
  std::optional<std::int64_t> unix_ms() const override;

 private:
  NowFn now_;
};

/// How many SNTP answers have arrived (logs, tests).
std::uint32_t sntp_updates();

/// The set-up page's words for the SNTP client (GET /api/setup "clock"):
/// off, waiting for the first answer of its server, or set by it how long
/// ago. `server` is copied (empty or `enabled` false: SNTP is off).
class SntpState final : public hal::ClockSync {
 public:
  using NowFn = Millis (*)();
  SntpState(NowFn now, bool enabled, std::string_view server);
  std::size_t describe(char* out, std::size_t capacity) const override;

 private:
  NowFn now_;
  bool enabled_;
  char server_[64] = {};
};

}  // namespace rotord::pico_w
