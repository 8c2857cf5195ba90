#pragma once
// The edge events of one GPIO line, drained whenever the line's event
// descriptor is readable (one asio loop, no thread) and whenever its owner
// asks (each tick), so none is lost between two ticks and the tick sees the
// newest. Shared by the anemometer's pulse counter and the MA3's edge timer.
#include <asio.hpp>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>

#include "gpio_line.hpp"

namespace rotord::linux_port {

class LineEdges {
 public:
  /// Gets each batch of edges read, oldest first; never an empty one.
  using OnEdges = std::function<void(std::span<const LineEdge>)>;

  LineEdges(std::unique_ptr<GpioLine> line, OnEdges on_edges);
  ~LineEdges();
  LineEdges(const LineEdges&) = delete;
  LineEdges& operator=(const LineEdges&) = delete;

  /// Starts watching the line's descriptor on `io` (no-op without one).
  void watch(asio::io_context& io);
  /// Reads every edge queued now.
  void drain();

 private:
  void arm();

  std::unique_ptr<GpioLine> line_;
  OnEdges on_edges_;
  std::unique_ptr<asio::posix::stream_descriptor> descriptor_;
};

}  // namespace rotord::linux_port
