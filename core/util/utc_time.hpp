#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>

#include "util/time.hpp"

namespace rotord {

/// Writes `unix_ms` as ISO 8601 UTC with milliseconds ("2026-11-23T17:40:11.250Z").
/// Hand-written (days-from-civil arithmetic) rather than gmtime_r: the core
/// makes no libc time calls, and the Pico's newlib has no time zone data to
/// gain from. Returns the length, 0 when it does not fit or the year is not
/// 0000..9999.
std::size_t format_utc_iso8601(std::int64_t unix_ms, char* out, std::size_t capacity);

/// Calendar time kept as an offset to the monotonic clock: set once from an
/// external source (SNTP), then read at any later monotonic time. No RTC
/// needed, and a step of the calendar time never disturbs the control tick.
class TimeBase {
 public:
  /// The calendar time was `unix_ms` at monotonic time `now`.
  void set(std::int64_t unix_ms, Millis now) {
    offset_ms_ = unix_ms - now;
    valid_ = true;
  }
  std::optional<std::int64_t> unix_ms(Millis now) const {
    if (!valid_) return std::nullopt;
    return offset_ms_ + now;
  }
  bool valid() const { return valid_; }

 private:
  std::int64_t offset_ms_ = 0;
  bool valid_ = false;
};

/// What lwIP's SNTP client reports (SNTP_SET_SYSTEM_TIME_US: seconds since
/// 1970 and microseconds) in milliseconds since 1970.
inline std::int64_t unix_ms_from_sntp(std::uint32_t sec, std::uint32_t us) {
  return static_cast<std::int64_t>(sec) * 1000 + static_cast<std::int64_t>(us / 1000);
}

}  // namespace rotord
