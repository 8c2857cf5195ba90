#pragma once
// An anemometer's pulses on a GPIO line through libgpiod's edge events
// (gpiod.wind, docs/care.md "Wind stow"): the kernel queues every edge in
// its interrupt handler, so none is lost between two ticks of the loop.
#include <asio.hpp>
#include <cstdint>
#include <memory>

#include "gpio_line.hpp"
#include "hal/pulse_counter.hpp"

namespace rotord::linux_port {

/// Counts the line's active edges (a reed contact closing; the line's
/// polarity is gpiod.inputs_active_low's). Edges are drained whenever the
/// event descriptor is readable (one asio loop, no thread) and at count().
class GpiodPulseCounter final : public hal::PulseCounter {
 public:
  explicit GpiodPulseCounter(std::unique_ptr<GpioLine> line);
  ~GpiodPulseCounter() override;
  GpiodPulseCounter(const GpiodPulseCounter&) = delete;
  GpiodPulseCounter& operator=(const GpiodPulseCounter&) = delete;

  /// Starts watching the line's descriptor on `io` (no-op without one).
  void watch(asio::io_context& io);
  std::uint32_t count() override;

 private:
  void drain();
  void arm();

  std::unique_ptr<GpioLine> line_;
  std::unique_ptr<asio::posix::stream_descriptor> descriptor_;
  std::uint32_t count_ = 0;
};

}  // namespace rotord::linux_port
