#pragma once
#include <cstdint>

#include "metrics/histogram.hpp"

namespace rotord::metrics {

/// What the control loop's tick schedule has done: GET /metrics reports it,
/// GET /healthz judges the loop alive by `last_tick_us`.
struct TickStats {
  std::uint64_t ticks = 0;     ///< ticks run
  std::uint64_t overruns = 0;  ///< deadlines skipped: the loop was a period or more late
  std::uint64_t rebases = 0;   ///< restarts of the schedule after a long stall
  std::int64_t last_tick_us = 0;
  /// How late each tick ran after its deadline: the loop's jitter.
  Histogram lateness;
  /// Time from one tick to the next: the period as it ran.
  Histogram interval;
};

/// The tick schedule as the metrics see it. The scheduler (TickScheduler, in
/// the loop layer above this one) implements it, so the metrics hold a
/// pointer to what they report without naming a layer they cannot reach.
class TickSource {
 public:
  virtual std::int64_t period_us() const = 0;
  virtual const TickStats& stats() const = 0;

 protected:
  TickSource() = default;
  TickSource(const TickSource&) = default;
  TickSource& operator=(const TickSource&) = default;
  ~TickSource() = default;  // never deleted through this interface
};

}  // namespace rotord::metrics
