#pragma once
// Keeps an attacker from flooding the log (an SD card, the journal, the
// Pico's USB log port): the first refusal from a source in a minute is
// written, the rest from it are counted and summed up in one line when its
// minute ends ("N more from ADDR in the last minute"), and the whole log
// writes at most lines_per_window lines a minute, summaries of a minute's
// end apart (at most one per source followed, and one of the lines over the
// budget). One gate serves the whole process: on Linux every line of the
// daemon's log goes through it (ports/linux/log.hpp), on the Pico W the
// web's; the web's access log shares it (web/web_auth.hpp,
// docs/security.md, "Logs"). Its budget is a LineBudget (line_budget.hpp),
// as the command log's is. Fixed storage, no heap.
#include <array>
#include <cstddef>
#include <cstdint>

#include "access/line_budget.hpp"
#include "access/peer.hpp"
#include "util/time.hpp"

namespace rotord::access {

class LogGate {
 public:
  static constexpr Millis kWindowMs = LineBudget::kWindowMs;
  /// A web access log of its own (the Pico W's, a test's).
  static constexpr unsigned kLinesPerWindow = 30;

  explicit LogGate(unsigned lines_per_window = kLinesPerWindow) : budget_(lines_per_window) {}
  /// Sources followed at once; one more takes the place of the oldest (its
  /// count is summed up then).
  static constexpr std::size_t kSources = 8;

  /// What a source's quiet lines came to.
  struct Summary {
    Peer source;
    std::uint32_t count = 0;  ///< 0: nothing to say
  };

  /// A refusal from `source`: true to write it. `evicted` is the summary of
  /// a source that had to give way (write it first when its count is not 0;
  /// it has been counted in the budget, and when over it, its count goes to
  /// the lines over the budget instead).
  bool admit(const Peer& source, Millis now, Summary& evicted);
  /// Any other line: true to write it (within the budget).
  bool admit_line(Millis now);
  /// The summaries due at `now`, one per call (count 0: none left), and then
  /// the lines dropped over the budget (source kind kUnknown).
  Summary next_due(Millis now);

  /// "N more from ADDR in the last minute" (an IPv6 source as its /64), or
  /// "N more log lines in the last minute, over the log's budget"; without
  /// a prefix or line end. Returns `out`.
  static const char* summary_text(const Summary& s, char* out, std::size_t size);

 private:
  struct Entry {
    bool used = false;
    Peer source;
    Millis since = 0;  ///< its minute began (its first line written)
    std::uint32_t quiet = 0;
  };

  LineBudget budget_;
  std::array<Entry, kSources> entries_{};
};

}  // namespace rotord::access
