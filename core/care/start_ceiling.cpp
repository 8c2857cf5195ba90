#include "care/start_ceiling.hpp"

namespace rotord::care {
namespace {
constexpr std::int64_t kBinCount = static_cast<std::int64_t>(StartCeiling::kBins);
}  // namespace

void StartCeiling::advance(Millis now) {
  const std::int64_t index = now / kBinMs;
  if (!started_) {
    bin_index_ = index;
    return;
  }
  // Clear every bin that left the window (all of them after a long pause).
  for (std::int64_t n = bin_index_ + 1; n <= index && n <= bin_index_ + kBinCount; ++n) {
    std::uint16_t& bin = bins_[static_cast<std::size_t>(n % kBins)];
    in_hour_ -= bin;
    bin = 0;
  }
  if (index > bin_index_) bin_index_ = index;
}

void StartCeiling::observe(std::uint32_t starts, Millis now) {
  advance(now);
  if (!started_) {
    started_ = true;
    last_starts_ = starts;
    return;
  }
  const std::uint32_t added = starts - last_starts_;
  last_starts_ = starts;
  if (added == 0) return;
  std::uint16_t& bin = bins_[static_cast<std::size_t>(bin_index_ % kBins)];
  // At most one start a tick: 12 000 in a bin, well within 16 bits.
  bin = static_cast<std::uint16_t>(bin + added);
  in_hour_ += added;
}

Millis StartCeiling::next_expiry(Millis now) const {
  for (std::int64_t n = bin_index_ - kBinCount + 1; n <= bin_index_; ++n) {
    if (n < 0) continue;
    if (bins_[static_cast<std::size_t>(n % kBins)] != 0) return (n + kBinCount) * kBinMs;
  }
  return now;
}

}  // namespace rotord::care
