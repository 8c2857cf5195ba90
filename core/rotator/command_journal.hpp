#pragma once
// Where the command layer tells each command that changes something (one
// log line: command/command_log.hpp writes it, docs/logging.md). The
// controller only carries the port's journal to it: every front end, from
// the line protocols to the buttons, reaches the controller and nothing
// else in common, and the core keeps no globals.
#include <string_view>

#include "access/peer.hpp"

namespace rotord {

/// One command as it ended, for the log.
struct CommandEntry {
  std::string_view what;   ///< the command ("goto", "stop", "move", ...)
  std::string_view args;   ///< its words ("az cw", a preset's name); may be empty
  std::string_view front;  ///< who took it: "rotctld", "rest", "mqtt", "buttons", ...
  access::Peer peer;       ///< the client (kUnknown: none, as for the buttons)
  /// Its numbers: degrees, or a speed in % (NaN: none).
  float az_deg;
  float el_deg;
  std::string_view outcome;  ///< "OK", or the refusal (an Error's name, "DENIED", "LOCKED")
};

class CommandJournal {
 public:
  virtual void record(const CommandEntry& entry) = 0;

 protected:
  ~CommandJournal() = default;
};

}  // namespace rotord
