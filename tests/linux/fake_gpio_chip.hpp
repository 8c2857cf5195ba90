#pragma once
// A GPIO chip at the libgpiod boundary (gpio_line.hpp) for tests: it records
// every request and the value of every line, and lets a test close switches
// and refuse lines as busy. The board state outlives the chip, so a test can
// check the lines after rotord released them.
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "gpio_line.hpp"

namespace rotord::testing {

struct FakeBoard {
  struct Line {
    linux_port::LineRequest request{};
    bool requested = false;
    bool active = false;  ///< logical value: outputs as written, inputs as set by the test
    int writes = 0;
    bool released = false;
    std::vector<linux_port::LineEdge> edges;  ///< edge lines: queued, oldest first
  };
  int line_count = 54;  ///< a Raspberry Pi's bank 0 and 1
  std::map<int, Line> lines;
  std::set<int> busy;
  bool closed = false;

  bool output_active(int offset) const {
    const auto it = lines.find(offset);
    return it != lines.end() && it->second.active;
  }
};

class FakeGpioLine final : public linux_port::GpioLine {
 public:
  FakeGpioLine(std::shared_ptr<FakeBoard> board, int offset)
      : board_(std::move(board)), offset_(offset) {}
  ~FakeGpioLine() override { line().released = true; }
  bool set_active(bool active) override {
    line().active = active;
    ++line().writes;
    return true;
  }
  int get_active() override { return line().active ? 1 : 0; }
  int event_fd() const override { return -1; }
  std::size_t read_edges(linux_port::LineEdge* out, std::size_t capacity) override {
    std::vector<linux_port::LineEdge>& q = line().edges;
    const std::size_t n = q.size() < capacity ? q.size() : capacity;
    for (std::size_t k = 0; k < n; ++k) out[k] = q[k];
    q.erase(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }

 private:
  FakeBoard::Line& line() { return board_->lines[offset_]; }
  std::shared_ptr<FakeBoard> board_;
  int offset_;
};

class FakeGpioChip final : public linux_port::GpioChip {
 public:
  explicit FakeGpioChip(std::shared_ptr<FakeBoard> board) : board_(std::move(board)) {}
  ~FakeGpioChip() override { board_->closed = true; }
  std::string describe() const override { return "/dev/gpiochip0 (fake)"; }
  std::unique_ptr<linux_port::GpioLine> request(const linux_port::LineRequest& r,
                                                std::string& error) override {
    const std::string where = std::string(r.key) + " = " + std::to_string(r.offset);
    if (r.offset >= board_->line_count) {
      error = where + ": line " + std::to_string(r.offset) + " does not exist";
      return nullptr;
    }
    if (board_->busy.count(r.offset) != 0) {
      error = where + ": line " + std::to_string(r.offset) + " of " + describe() + " is busy";
      return nullptr;
    }
    FakeBoard::Line& line = board_->lines[r.offset];
    line = {};
    line.request = r;
    line.requested = true;
    return std::make_unique<FakeGpioLine>(board_, r.offset);
  }

 private:
  std::shared_ptr<FakeBoard> board_;
};

}  // namespace rotord::testing
