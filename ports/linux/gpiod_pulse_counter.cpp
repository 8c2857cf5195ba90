#include "gpiod_pulse_counter.hpp"

#include <iterator>

namespace rotord::linux_port {

GpiodPulseCounter::GpiodPulseCounter(std::unique_ptr<GpioLine> line) : line_(std::move(line)) {}

GpiodPulseCounter::~GpiodPulseCounter() {
  if (descriptor_) {
    // The line owns the descriptor: asio must not close it.
    asio::error_code ignored;
    descriptor_->cancel(ignored);
    descriptor_->release();
  }
}

void GpiodPulseCounter::watch(asio::io_context& io) {
  const int fd = line_->event_fd();
  if (fd < 0) return;
  descriptor_ = std::make_unique<asio::posix::stream_descriptor>(io, fd);
  arm();
}

void GpiodPulseCounter::arm() {
  descriptor_->async_wait(asio::posix::stream_descriptor::wait_read, [this](std::error_code ec) {
    if (ec) return;  // cancelled: the counter is being destroyed
    drain();
    arm();
  });
}

void GpiodPulseCounter::drain() {
  LineEdge edges[64];
  for (;;) {
    const std::size_t n = line_->read_edges(edges, std::size(edges));
    for (std::size_t k = 0; k < n; ++k)
      if (edges[k].rising) ++count_;  // wraps at 2^32, as the core expects
    if (n < std::size(edges)) return;
  }
}

std::uint32_t GpiodPulseCounter::count() {
  drain();
  return count_;
}

}  // namespace rotord::linux_port
