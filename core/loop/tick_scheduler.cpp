#include "loop/tick_scheduler.hpp"

namespace rotord {

// Lateness: a healthy loop wakes well within a millisecond; 10 ms and more
// means whole ticks were skipped.
const std::int64_t TickScheduler::kLatenessBoundsUs[10] = {50,   100,  250,   500,   1000,
                                                           2000, 5000, 10000, 50000, 100000};
// Interval: tight around the 10 ms period, then coarser for overruns.
const std::int64_t TickScheduler::kIntervalBoundsUs[11] = {5000,  9000,  9500,  9900,  10100, 10500,
                                                           11000, 15000, 20000, 50000, 100000};

TickScheduler::TickScheduler(std::int64_t period_us, std::int64_t rebase_after_us)
    : period_us_(period_us > 0 ? period_us : 1),
      rebase_after_us_(rebase_after_us),
      stats_{0,
             0,
             0,
             0,
             metrics::Histogram(kLatenessBoundsUs),
             metrics::Histogram(kIntervalBoundsUs)} {}

void TickScheduler::start(std::int64_t now_us) {
  start_us_ = now_us;
  index_ = 1;
  next_us_ = start_us_ + period_us_;
}

bool TickScheduler::poll(std::int64_t now_us) {
  if (now_us < next_us_) return false;
  const std::int64_t late_us = now_us - next_us_;
  // Deadlines after this one that have passed too: skipped, not caught up.
  const std::int64_t missed = late_us / period_us_;
  stats_.overruns += static_cast<std::uint64_t>(missed);
  if (late_us >= rebase_after_us_) {
    ++stats_.rebases;
    start(now_us);
  } else {
    index_ += 1 + missed;
    next_us_ = start_us_ + index_ * period_us_;
  }
  stats_.lateness.add(late_us);
  if (stats_.ticks > 0) stats_.interval.add(now_us - stats_.last_tick_us);
  ++stats_.ticks;
  stats_.last_tick_us = now_us;
  return true;
}

}  // namespace rotord
