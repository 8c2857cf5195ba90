#pragma once
// Keeps an attacker from flooding the log (an SD card, the journal, the
// Pico's USB log port): the first refusal from a source in a minute is
// written, the rest from it are counted and summed up in one line when its
// minute ends ("N more from ADDR in the last minute"), and the whole sink
// writes at most kLinesPerWindow lines a minute, summaries apart
// (docs/security.md, "Logs"). Fixed storage, no heap.
#include <array>
#include <cstddef>
#include <cstdint>

#include "access/peer.hpp"
#include "util/time.hpp"

namespace rotord::access {

class LogGate {
 public:
  static constexpr Millis kWindowMs = 60000;
  static constexpr unsigned kLinesPerWindow = 30;
  /// Sources followed at once; one more takes the place of the oldest (its
  /// count is summed up then).
  static constexpr std::size_t kSources = 8;

  /// What a source's quiet lines came to.
  struct Summary {
    Peer source;
    std::uint32_t count = 0;  ///< 0: nothing to say
  };

  /// A refusal from `source`: true to write it. `evicted` is the summary of
  /// a source that had to give way (write it first when its count is not 0).
  bool admit(const Peer& source, Millis now, Summary& evicted);
  /// Any other line: true to write it (within the budget).
  bool admit_line(Millis now);
  /// The summaries due at `now`, one per call (count 0: none left), and then
  /// the lines dropped over the budget (source kind kUnknown).
  Summary next_due(Millis now);

 private:
  struct Entry {
    bool used = false;
    Peer source;
    Millis since = 0;  ///< its minute began (its first line written)
    std::uint32_t quiet = 0;
  };
  void roll(Millis now);

  std::array<Entry, kSources> entries_{};
  Millis window_start_ = 0;
  bool started_ = false;
  unsigned lines_ = 0;          ///< written in this window
  std::uint32_t dropped_ = 0;   ///< over the budget in the last window
  std::uint32_t dropping_ = 0;  ///< over the budget in this window
};

}  // namespace rotord::access
