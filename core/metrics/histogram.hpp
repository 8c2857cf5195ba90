#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rotord::metrics {

/// Counts of observations in fixed buckets, for a Prometheus histogram
/// (`_bucket{le=...}`, `_sum`, `_count`). The bounds are the caller's
/// constant table; adding an observation is a few compares and no heap, so it
/// may run in the control loop on the Pico.
class Histogram {
 public:
  static constexpr std::size_t kMaxBuckets = 12;

  /// `upper_bounds_us`: ascending, at most kMaxBuckets, static storage. An
  /// observation above the last bound counts only in +Inf (count()).
  explicit Histogram(std::span<const std::int64_t> upper_bounds_us)
      : bounds_(upper_bounds_us.size() > kMaxBuckets ? upper_bounds_us.first(kMaxBuckets)
                                                     : upper_bounds_us) {}

  void add(std::int64_t value_us) {
    for (std::size_t n = 0; n < bounds_.size(); ++n) {
      if (value_us <= bounds_[n]) {
        ++counts_[n];
        break;
      }
    }
    ++count_;
    sum_us_ += value_us;
  }

  std::span<const std::int64_t> bounds_us() const { return bounds_; }
  /// Observations in bucket `n` alone (not cumulative).
  std::uint64_t bucket(std::size_t n) const { return n < bounds_.size() ? counts_[n] : 0; }
  std::uint64_t count() const { return count_; }
  std::int64_t sum_us() const { return sum_us_; }

 private:
  std::span<const std::int64_t> bounds_;
  std::array<std::uint64_t, kMaxBuckets> counts_{};
  std::uint64_t count_ = 0;
  std::int64_t sum_us_ = 0;
};

}  // namespace rotord::metrics
