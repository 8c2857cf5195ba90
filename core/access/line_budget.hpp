#pragma once
// A log's budget of lines a minute: what is over it is counted, not
// written, and said in one line when the minute ends. The arithmetic of
// every budget in the process: the log gate's (log_gate.hpp: the daemon's
// log on Linux, the web's on the Pico W) and the command log's
// (command/command_log.hpp), which follows no sources and so needs none of
// the gate's table. Fixed storage, no heap.
#include <cstdint>

#include "util/time.hpp"

namespace rotord::access {

class LineBudget {
 public:
  static constexpr Millis kWindowMs = 60000;

  explicit LineBudget(unsigned lines_per_window) : lines_per_window_(lines_per_window) {}

  /// Starts a new minute when the last one has ended; the first call starts
  /// the first minute.
  void roll(Millis now);
  /// A line: true to write it (within this minute's budget), else counted.
  bool admit(Millis now);
  /// Lines counted over the budget without asking (a summary's count).
  void count_over(std::uint32_t lines) { dropping_ += lines; }
  /// The lines over the budget in the minutes ended by `now`, once (then 0).
  std::uint32_t take_over(Millis now);

 private:
  unsigned lines_per_window_;
  Millis window_start_ = 0;
  bool started_ = false;
  unsigned lines_ = 0;          ///< written in this window
  std::uint32_t dropped_ = 0;   ///< over the budget in the windows ended
  std::uint32_t dropping_ = 0;  ///< over the budget in this window
};

}  // namespace rotord::access
