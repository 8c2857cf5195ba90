#pragma once
// An anemometer's pulses on a GPIO line through libgpiod's edge events
// (gpiod.wind, docs/care.md "Wind stow"): the kernel queues every edge in
// its interrupt handler, so none is lost between two ticks of the loop.
#include <asio.hpp>
#include <cstdint>
#include <memory>

#include "gpio_line.hpp"
#include "hal/pulse_counter.hpp"
#include "line_edges.hpp"

namespace rotord::linux_port {

/// Counts the line's active edges (a reed contact closing; the line's
/// polarity is gpiod.inputs_active_low's). Edges are drained whenever the
/// event descriptor is readable (one asio loop, no thread) and at count().
class GpiodPulseCounter final : public hal::PulseCounter {
 public:
  explicit GpiodPulseCounter(std::unique_ptr<GpioLine> line);

  /// Starts watching the line's descriptor on `io` (no-op without one).
  void watch(asio::io_context& io) { edges_.watch(io); }
  std::uint32_t count() override;

 private:
  std::uint32_t count_ = 0;
  LineEdges edges_;  // after count_, which its handler writes
};

}  // namespace rotord::linux_port
