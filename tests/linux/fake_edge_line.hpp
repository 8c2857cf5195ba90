#pragma once
// A both-edges GPIO line (gpio_line.hpp) whose queued edges a test provides,
// for the MA3's edge input and LineEdges. Its event descriptor is -1 (read
// only when asked), or one the test makes readable (a pipe's read end).
#include <cstddef>
#include <deque>

#include "gpio_line.hpp"

namespace rotord::testing {

class FakeEdgeLine final : public linux_port::GpioLine {
 public:
  explicit FakeEdgeLine(int event_fd = -1) : fd_(event_fd) {}
  std::deque<linux_port::LineEdge> queued;
  bool set_active(bool) override { return false; }
  int get_active() override { return -1; }
  int event_fd() const override { return fd_; }
  std::size_t read_edges(linux_port::LineEdge* out, std::size_t capacity) override {
    std::size_t n = 0;
    while (n < capacity && !queued.empty()) {
      out[n++] = queued.front();
      queued.pop_front();
    }
    return n;
  }

 private:
  int fd_;
};

}  // namespace rotord::testing
