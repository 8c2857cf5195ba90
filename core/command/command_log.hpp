#pragma once
// The log line of every command that changes something (docs/logging.md):
// written here, in the command layer, once for every front end, never by
// the front ends themselves. One line a command:
//   command goto az 120.0 el 30.0 from rotctld (192.168.1.20): OK
//   command goto az 400.0 from rest (192.168.1.20): OUT OF RANGE
//   command P from rotctld (192.168.1.30): DENIED
// Queries (get the position, the status) write nothing: a rotctld client
// polls `p` five times a second.
//
// Nobody floods it: the same command (and words) from the same client with
// the same outcome again within a minute of its line is counted, not written, and
// summed up in one line when that minute ends ("command goto from rotctld
// (192.168.1.20): OK, 599 more in the last minute"), so a tracker that
// streams go-tos writes two lines a minute, whatever its rate. Four such
// repeats are followed at once (a fifth's arrival sums up the oldest), and
// the whole command log writes at most kLinesPerWindow lines a minute, the
// rest counted in one line: that budget is an access::LineBudget of its
// own, the arithmetic every log gate of the process keeps its budget with.
// Fixed storage, no heap: it runs on the Pico W.
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

#include "access/line_budget.hpp"
#include "rotator/controller.hpp"
#include "util/byte_sink.hpp"
#include "util/time.hpp"

namespace rotord::command {

/// Who sent a command: its front end ("rotctld", "rest", "buttons", ...)
/// and its client (kUnknown when there is none, as for the buttons).
struct Origin {
  std::string_view front;
  access::Peer peer;
};

/// Tells the controller's journal (when attached) that `what` from `from`
/// ended in `outcome`; returns `outcome`, so a command ends with
/// `return told(...)`. Numbers NaN when not given.
Error told(Controller& controller, const Origin& from, std::string_view what, Error outcome,
           float az_deg = NAN, float el_deg = NAN, std::string_view args = {});
/// The same with the outcome in words: a refusal with no Error of its own
/// ("DENIED", "LOCKED").
void told(Controller& controller, const Origin& from, std::string_view what,
          std::string_view outcome, float az_deg = NAN, float el_deg = NAN,
          std::string_view args = {});

/// The journal a port attaches to its controller: lines to `out`, one
/// write() each, without "rotord: " and without a line end (the port's
/// log adds them: the journal's priority on Linux, the USB log port's
/// "rotord: " on the Pico W).
class CommandLog final : public CommandJournal {
 public:
  static constexpr Millis kWindowMs = access::LineBudget::kWindowMs;
  static constexpr unsigned kLinesPerWindow = 30;
  static constexpr std::size_t kRepeats = 4;

  /// The budget's minutes are counted from the clock's 0, as the repeats'
  /// are (a budget's first minute begins at its first line otherwise).
  explicit CommandLog(ByteSink& out) : out_(out) { budget_.roll(0); }
  void record(const CommandEntry& entry) override;
  /// The port's clock: the summaries that are due are written now. Call
  /// every pass of the port's loop.
  void poll(Millis now);

 private:
  /// A command line written, and how often the same came since.
  struct Repeat {
    bool used = false;
    std::string_view what;
    std::string_view front;
    std::string_view outcome;
    std::uint32_t args = 0;  ///< a hash of the words: "az cw" is not "az stop"
    access::Peer peer;
    Millis since = 0;
    std::uint32_t count = 0;
  };
  void sum_up(Repeat& r);
  void write(const char* format, ...) __attribute__((format(printf, 2, 3)));

  ByteSink& out_;
  std::array<Repeat, kRepeats> repeats_{};
  /// The last poll's time: a line counts in the budget's minute of then,
  /// the repeats summed up at a minute's end included.
  Millis now_ = 0;
  access::LineBudget budget_{kLinesPerWindow};
};

}  // namespace rotord::command
