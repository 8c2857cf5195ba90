#pragma once
#include <cstdint>

#include "metrics/tick_source.hpp"

namespace rotord {

/// When a port's loop runs the control tick: the n-th tick is due at
/// start + n x period, on an absolute schedule, so wake-up latency never adds
/// up into drift (re-arming "period after the last tick" ran at 10.23 ms
/// instead of 10). Pure arithmetic on times the port passes in (microseconds
/// of a monotonic clock), so it is unit-tested with a clock the test owns.
///
/// A late loop runs one tick, never a burst of catch-up ticks: the controller
/// works from the time it is given, not from a tick count, and a burst would
/// only delay the sockets further. Deadlines that passed meanwhile are
/// skipped and counted as overruns; the schedule keeps its phase. After a
/// stall of rebase_after_us or more (a suspended host, a debugger, a stepped
/// clock) the schedule starts again from that moment, and that is counted too.
class TickScheduler final : public metrics::TickSource {
 public:
  static constexpr std::int64_t kDefaultRebaseAfterUs = 1'000'000;

  /// Declared in the metrics layer, which reports them (the scheduler is
  /// the metrics' TickSource, so they never name this layer).
  using Stats = metrics::TickStats;

  /// Bucket bounds of Stats::lateness and Stats::interval (microseconds).
  static const std::int64_t kLatenessBoundsUs[10];
  static const std::int64_t kIntervalBoundsUs[11];

  explicit TickScheduler(std::int64_t period_us,
                         std::int64_t rebase_after_us = kDefaultRebaseAfterUs);

  /// The first tick is due one period after `now_us`.
  void start(std::int64_t now_us);
  /// When the next tick is due; the port sleeps until then.
  std::int64_t deadline_us() const { return next_us_; }
  /// Call on every wake-up. True: a tick is due, run exactly one now; the
  /// next deadline has been set. False: woke early, sleep until deadline_us().
  bool poll(std::int64_t now_us);

  std::int64_t period_us() const override { return period_us_; }
  const Stats& stats() const override { return stats_; }

 private:
  std::int64_t period_us_;
  std::int64_t rebase_after_us_;
  std::int64_t start_us_ = 0;
  std::int64_t index_ = 0;  ///< the next tick is due at start_us_ + index_ x period
  std::int64_t next_us_ = 0;
  Stats stats_;
};

}  // namespace rotord
