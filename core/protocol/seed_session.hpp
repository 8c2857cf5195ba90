#pragma once
#include "protocol/line_assembler.hpp"
#include "protocol/session.hpp"

namespace rotord::protocol {

/// The `$cmd,arg` serial format of the relay-sequenced controller rotord grew
/// from (docs/protocols/seed.md): `$E` enable, `$D` disable and stop, `$S,n`
/// speed, `$R,cw|ccw` run in a direction, plus `$Q` state. One command per
/// line (CR, LF or CRLF); every command is answered with `$OK,...` or
/// `$ERR,<REASON>` and CR LF. Run commands need `$E` first in this session,
/// as the relay controller needed its drive enabled; a new session starts
/// disabled, so a reconnecting client cannot restart a motion by accident.
class SeedSession final : public Session {
 public:
  static constexpr std::size_t kMaxLineLength = 64;
  static constexpr std::string_view kTooManyConnections = "$ERR,BUSY\r\n";

  explicit SeedSession(Controller& controller) : controller_(controller) {}

  void receive(std::string_view bytes, ByteSink& out) override;

  /// Handles one command line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

  bool enabled() const { return enabled_; }

 private:
  void write_state(ByteSink& out);

  Controller& controller_;
  LineAssembler<kMaxLineLength> lines_;
  bool enabled_ = false;
};

}  // namespace rotord::protocol
