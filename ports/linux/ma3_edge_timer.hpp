#pragma once
// The MA3 encoder's PWM read from GPIO edge events on Linux: the kernel
// timestamps every edge when it happens (in its interrupt handler), so the
// high time and the period come from those timestamps, not from when rotord
// gets to read them. The duty ratio is decoded by the core (ma3_sensor.*).
#include <array>
#include <asio.hpp>
#include <cstdint>
#include <functional>
#include <memory>

#include "gpio_line.hpp"
#include "hal/pwm_in.hpp"
#include "line_edges.hpp"

namespace rotord::linux_port {

/// Assembles edges into PWM periods (rise, fall, next rise). A lost edge (two
/// rises or two falls in a row: the kernel's event queue overflowed) or a
/// timestamp going backwards restarts the assembly, so it never yields a
/// period made of edges from different frames.
///
/// take() averages the periods completed since the previous take() whose
/// length agrees with the newest one within 1/8: averaging a few frames (a
/// 10 ms tick holds ~2 of a 12-bit part, ~10 of a 10-bit one) divides the
/// interrupt-latency jitter of the timestamps, while a period that a noise
/// edge split or merged is left out instead of skewing the mean.
class Ma3EdgeTimer {
 public:
  /// No edge for this long: the encoder is unplugged (periods are 1-4 ms).
  static constexpr std::uint64_t kTimeoutNs = 100'000'000;
  static constexpr std::size_t kMaxPeriods = 32;

  /// One edge; `now_ns` is when rotord saw it (its own monotonic clock), for
  /// the timeout, so the timestamps' clock does not matter.
  void on_edge(const LineEdge& edge, std::uint64_t now_ns);
  /// The mean of the periods since the last call, else the last one again;
  /// invalid after kTimeoutNs without an edge, or before the first period.
  hal::PwmPeriod take(std::uint64_t now_ns);

 private:
  struct Period {
    std::uint64_t high_ns;
    std::uint64_t low_ns;
  };
  void restart() { have_rise_ = have_fall_ = false; }

  bool have_rise_ = false;
  bool have_fall_ = false;
  std::uint64_t rise_ns_ = 0;
  std::uint64_t fall_ns_ = 0;
  std::uint64_t last_edge_ns_ = 0;  ///< kernel time of the previous edge
  bool seen_edge_ = false;
  std::uint64_t last_seen_ns_ = 0;  ///< rotord's time of the last edge
  std::array<Period, kMaxPeriods> periods_{};
  std::size_t count_ = 0;  ///< periods since the last take(), newest at count_-1
  hal::PwmPeriod last_;
};

/// An MA3 on a both-edges GPIO line, as the core's hal::PwmIn. Edges are
/// drained whenever the line's event descriptor is readable (one asio loop,
/// no thread) and again at each read(), so the tick sees the newest ones.
class GpiodMa3Input final : public hal::PwmIn {
 public:
  using Clock = std::function<std::uint64_t()>;  ///< monotonic ns

  GpiodMa3Input(std::unique_ptr<GpioLine> line, Clock clock);

  /// Starts watching the line's descriptor on `io` (no-op without one).
  void watch(asio::io_context& io) { edges_.watch(io); }
  hal::PwmPeriod read() override;

 private:
  Clock clock_;
  Ma3EdgeTimer timer_;
  LineEdges edges_;  // after the clock and timer, which its handler uses
};

/// CLOCK_MONOTONIC in ns.
std::uint64_t monotonic_ns();

}  // namespace rotord::linux_port
