#pragma once
#include <asio.hpp>
#include <functional>
#include <string>

#include "util/time.hpp"

namespace rotord::linux_port {

/// `rotord --clock manual`: controller time stands still until a test moves
/// it, as ArduPilot's SITL and rusEFI's test helper own time. The commands
/// arrive on standard input, never on a network port:
///
///     advance <ms>   runs the control tick for <ms> of controller time
///                    (rounded up to whole 10 ms ticks), then prints
///                    "rotord: clock <now_ms>"
///     now            prints "rotord: clock <now_ms>"
///
/// Network timeouts and push periods stay on the wall clock.
class ClockControl {
 public:
  /// Runs `ms` of controller time; returns the controller time after it.
  using Advance = std::function<Millis(Millis ms)>;
  /// The longest single advance: a day of controller time.
  static constexpr Millis kMaxAdvanceMs = 24LL * 3600 * 1000;

  ClockControl(asio::io_context& io, Advance advance);
  void start();

 private:
  void read_next();
  void handle(const std::string& line);
  /// Runs `fn` after `hops` trips through the loop's handler queue.
  void after_queued_handlers(int hops, std::function<void()> fn);

  /// Trips through the handler queue before an advance: accept, read, and one
  /// to spare.
  static constexpr int kHandlerHops = 3;

  asio::io_context& io_;
  asio::posix::stream_descriptor in_;
  Advance advance_;
  std::string buffer_;
};

}  // namespace rotord::linux_port
