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

void StartCeiling::observe(std::uint32_t starts, Millis now, int per_hour) {
  advance(now);
  // The pace's bucket: full when the ceiling is set or changed.
  const float burst = per_hour >= 10 ? static_cast<float>(per_hour) / 10.0f : 1.0f;
  if (per_hour != per_hour_) {
    per_hour_ = per_hour;
    tokens_ = burst;
  } else if (per_hour > 0 && now > last_now_) {
    const float refill_per_ms = (static_cast<float>(per_hour) - burst) / 3600000.0f;
    tokens_ += refill_per_ms * static_cast<float>(now - last_now_);
    if (tokens_ > burst) tokens_ = burst;
  }
  last_now_ = now;
  if (!started_) {
    started_ = true;
    last_starts_ = starts;
    return;
  }
  const std::uint32_t added = starts - last_starts_;
  last_starts_ = starts;
  if (added == 0) return;
  std::uint16_t& bin = bins_[static_cast<std::size_t>(bin_index_ % kBinCount)];
  // At most one start a tick: 12 000 in a bin, well within 16 bits.
  bin = static_cast<std::uint16_t>(bin + added);
  in_hour_ += added;
  // Jogs are never held, so the bucket may run dry; it does not owe.
  tokens_ -= static_cast<float>(added);
  if (tokens_ < 0.0f) tokens_ = 0.0f;
}

Millis StartCeiling::next_expiry(Millis now) const {
  for (std::int64_t n = bin_index_ - kBinCount + 1; n <= bin_index_; ++n) {
    if (n < 0) continue;
    if (bins_[static_cast<std::size_t>(n % kBins)] != 0) return (n + kBinCount) * kBinMs;
  }
  return now;
}

}  // namespace rotord::care
