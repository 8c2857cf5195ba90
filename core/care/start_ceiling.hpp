#pragma once
#include <array>
#include <cstdint>

#include "util/time.hpp"

namespace rotord::care {

/// The starts-per-hour ceiling of one axis (care.max_starts_h, docs/care.md):
/// counts the motor's starts in a sliding hour and says when another start
/// would pass the ceiling. The hour is kept in 31 bins of 2 minutes (62
/// bytes, no heap): a start is allowed while the bins, the current one and
/// the 30 before it, hold fewer than the ceiling. They span at least the
/// last 60 minutes, so no 60 minutes ever hold more starts than the ceiling
/// (the price: a start may wait up to 2 minutes longer than it strictly
/// had to).
class StartCeiling {
 public:
  static constexpr Millis kBinMs = 120000;
  static constexpr std::size_t kBins = 31;

  /// `starts`: the axis's start count (AxisStatus::moves), whose growth
  /// since the last call is counted now.
  void observe(std::uint32_t starts, Millis now);
  /// Starts in the sliding hour (the bins' sum).
  std::uint32_t starts_in_hour() const { return in_hour_; }
  /// Whether another start stays within `per_hour` (0: no ceiling).
  bool allows_start(int per_hour) const {
    return per_hour <= 0 || in_hour_ < static_cast<std::uint32_t>(per_hour);
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
};

}  // namespace rotord::care
