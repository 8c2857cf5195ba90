#include "line_edges.hpp"

#include <iterator>
#include <utility>

namespace rotord::linux_port {

LineEdges::LineEdges(std::unique_ptr<GpioLine> line, OnEdges on_edges)
    : line_(std::move(line)), on_edges_(std::move(on_edges)) {}

LineEdges::~LineEdges() {
  // The descriptor belongs to the line (libgpiod closes it on release):
  // asio must not close it.
  if (descriptor_) {
    std::error_code ignored;
    descriptor_->cancel(ignored);
    descriptor_->release();
  }
}

void LineEdges::watch(asio::io_context& io) {
  const int fd = line_->event_fd();
  if (fd < 0) return;
  descriptor_ = std::make_unique<asio::posix::stream_descriptor>(io, fd);
  arm();
}

void LineEdges::arm() {
  descriptor_->async_wait(asio::posix::stream_descriptor::wait_read, [this](std::error_code ec) {
    if (ec) return;  // cancelled: the owner is being destroyed
    drain();
    arm();
  });
}

void LineEdges::drain() {
  LineEdge edges[64];
  for (;;) {
    const std::size_t n = line_->read_edges(edges, std::size(edges));
    if (n == 0) return;
    on_edges_(std::span<const LineEdge>(edges, n));
    if (n < std::size(edges)) return;
  }
}

}  // namespace rotord::linux_port
