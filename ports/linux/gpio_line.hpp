#pragma once
// The hardware boundary of `rotord --hw gpiod`: one GPIO chip and its lines.
// gpiod_chip.cpp implements it over libgpiod 1.6's C API; the tests put a
// fake here (and only here) to check the I/O layer above it.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace rotord::linux_port {

enum class LineMode : std::uint8_t { kOutput, kInput, kBothEdges };

/// Bias of an input line, in the order of the gpiod.input_bias choices.
enum class LineBias : std::uint8_t { kPullUp, kPullDown, kDisable, kAsIs };

struct LineRequest {
  const char* key;  ///< the setting that names the line, for messages
  int offset;       ///< line offset on the chip (the BCM GPIO number on a Pi)
  LineMode mode;
  bool active_low;  ///< the kernel inverts: active = low level
  LineBias bias = LineBias::kAsIs;
};

/// One edge of an edge-event line, with the kernel's timestamp.
struct LineEdge {
  bool rising;
  std::uint64_t timestamp_ns;
};

/// A requested line. Values are logical: true = active (energised relay,
/// closed switch), whatever the line's polarity.
class GpioLine {
 public:
  virtual ~GpioLine() = default;
  /// Outputs. False on an I/O error.
  virtual bool set_active(bool active) = 0;
  /// Inputs: 1 active, 0 inactive, -1 on an I/O error.
  virtual int get_active() = 0;
  /// Edge lines: a descriptor that becomes readable when edges are queued,
  /// or -1 (fakes), in which case read_edges() is only called from the tick.
  virtual int event_fd() const = 0;
  /// Edge lines: the edges queued now, oldest first, without waiting.
  virtual std::size_t read_edges(LineEdge* out, std::size_t capacity) = 0;
};

class GpioChip {
 public:
  virtual ~GpioChip() = default;
  /// "/dev/gpiochip0 (pinctrl-bcm2711)", for messages.
  virtual std::string describe() const = 0;
  /// Requests one line, outputs inactive. On failure returns nullptr and sets
  /// `error` to a sentence naming the key, the line and the chip.
  virtual std::unique_ptr<GpioLine> request(const LineRequest& request, std::string& error) = 0;
};

/// Opens /dev/gpiochipN through libgpiod; nullptr and `error` when it is
/// missing or cannot be opened.
std::unique_ptr<GpioChip> open_gpiod_chip(int number, std::string& error);

}  // namespace rotord::linux_port
