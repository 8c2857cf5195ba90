#include "ma3_edge_timer.hpp"

#include <chrono>

namespace rotord::linux_port {

void Ma3EdgeTimer::on_edge(const LineEdge& edge, std::uint64_t now_ns) {
  last_seen_ns_ = now_ns;
  const std::uint64_t t = edge.timestamp_ns;
  const bool backwards = seen_edge_ && t <= last_edge_ns_;
  seen_edge_ = true;
  last_edge_ns_ = t;
  if (backwards) {
    restart();
    return;
  }
  if (!edge.rising) {
    if (have_rise_ && !have_fall_) {
      fall_ns_ = t;
      have_fall_ = true;
    } else {
      restart();  // a rise was lost: this fall ends an unknown high time
    }
    return;
  }
  if (have_rise_ && have_fall_) {
    if (count_ == kMaxPeriods) {  // not read for a while: keep the newest
      for (std::size_t k = 1; k < kMaxPeriods; ++k) periods_[k - 1] = periods_[k];
      --count_;
    }
    periods_[count_++] = {fall_ns_ - rise_ns_, t - fall_ns_};
  }
  // Two rises in a row (a fall was lost) give no period; both cases start
  // the next one here.
  have_rise_ = true;
  have_fall_ = false;
  rise_ns_ = t;
}

hal::PwmPeriod Ma3EdgeTimer::take(std::uint64_t now_ns) {
  if (!seen_edge_ || now_ns - last_seen_ns_ > kTimeoutNs) {
    count_ = 0;
    restart();
    last_ = {};
    return last_;
  }
  if (count_ == 0) return last_;
  const Period& newest = periods_[count_ - 1];
  const std::uint64_t newest_ns = newest.high_ns + newest.low_ns;
  std::uint64_t high_ns = 0, low_ns = 0, n = 0;
  for (std::size_t k = 0; k < count_; ++k) {
    const std::uint64_t length = periods_[k].high_ns + periods_[k].low_ns;
    const std::uint64_t diff = length > newest_ns ? length - newest_ns : newest_ns - length;
    if (diff * 8 > newest_ns) continue;
    high_ns += periods_[k].high_ns;
    low_ns += periods_[k].low_ns;
    ++n;
  }
  count_ = 0;
  // Rounded to whole microseconds, the unit of hal::PwmPeriod.
  last_.high_us = static_cast<std::uint32_t>((high_ns / n + 500) / 1000);
  last_.low_us = static_cast<std::uint32_t>((low_ns / n + 500) / 1000);
  last_.valid = true;
  return last_;
}

std::uint64_t monotonic_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::steady_clock::now().time_since_epoch())
                                        .count());
}

GpiodMa3Input::GpiodMa3Input(std::unique_ptr<GpioLine> line, Clock clock)
    : clock_(std::move(clock)), edges_(std::move(line), [this](std::span<const LineEdge> edges) {
        const std::uint64_t now = clock_();
        for (const LineEdge& e : edges) timer_.on_edge(e, now);
      }) {}

hal::PwmPeriod GpiodMa3Input::read() {
  edges_.drain();
  return timer_.take(clock_());
}

}  // namespace rotord::linux_port
