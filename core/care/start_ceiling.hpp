#pragma once
#include <array>
#include <cstdint>

#include "util/time.hpp"

namespace rotord::care {

/// The starts-per-hour ceiling of one axis (care.max_starts_h, docs/care.md).
/// Two rules, no heap (about 80 bytes):
///
/// - Pace: a token bucket holding up to a tenth of the ceiling (at least 1)
///   and refilled at the rest of it per hour. A start takes a token; a
///   go-to finding none waits (its tolerance widened), so a tracker's stream
///   is spread over the hour at the ceiling's rate rather than spending the
///   hour's starts in ten minutes and standing still for fifty. Any hour
///   holds at most burst + refill = the ceiling.
/// - Cap: the starts of the sliding hour, kept in 31 bins of 2 minutes (the
///   current one and the 30 before it span at least the last 60 minutes),
///   never pass the ceiling, whatever the pace rule allowed (a change of the
///   setting, jogs).
class StartCeiling {
 public:
  static constexpr Millis kBinMs = 120000;
  static constexpr std::size_t kBins = 31;

  /// `starts`: the axis's start count (AxisStatus::moves), whose growth
  /// since the last call is counted now; `per_hour`: the ceiling (0: none).
  void observe(std::uint32_t starts, Millis now, int per_hour);
  /// Starts in the sliding hour (the bins' sum).
  std::uint32_t starts_in_hour() const { return in_hour_; }
  /// Whether another start stays within `per_hour` (0: no ceiling).
  bool allows_start(int per_hour) const {
    return per_hour <= 0 || (tokens_ >= 1.0f && in_hour_ < static_cast<std::uint32_t>(per_hour));
  }
  /// When the oldest bin with a start leaves the window (a start may be
  /// allowed again then), or `now` when no start was counted.
  Millis next_expiry(Millis now) const;

 private:
  void advance(Millis now);

  std::array<std::uint16_t, kBins> bins_{};
  std::int64_t bin_index_ = 0;  ///< the current bin's number (now / kBinMs)
  bool started_ = false;
  std::uint32_t last_starts_ = 0;
  std::uint32_t in_hour_ = 0;
  float tokens_ = 0.0f;  ///< starts the pace allows now
  int per_hour_ = 0;     ///< the ceiling the bucket was filled for
  Millis last_now_ = 0;
};

}  // namespace rotord::care
