#include "gpiod_pulse_counter.hpp"

namespace rotord::linux_port {

GpiodPulseCounter::GpiodPulseCounter(std::unique_ptr<GpioLine> line)
    : edges_(std::move(line), [this](std::span<const LineEdge> edges) {
        for (const LineEdge& e : edges)
          if (e.rising) ++count_;  // wraps at 2^32, as the core expects
      }) {}

std::uint32_t GpiodPulseCounter::count() {
  edges_.drain();
  return count_;
}

}  // namespace rotord::linux_port
