#pragma once
#include <cstdint>
#include <span>

#include "protocol/line_assembler.hpp"
#include "protocol/line_reply.hpp"
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
  std::string_view front() const override { return "seed"; }
  static constexpr std::size_t kMaxLineLength = 64;
  static constexpr std::size_t kMaxReplyLength = 128;
  static constexpr std::string_view kTooManyConnections = "$ERR,BUSY\r\n";
  /// CR LF lines; a reply that cannot fit is the too-long error.
  static constexpr ReplyRules kReplyRules{"\r\n", "$ERR,TOOLONG\r\n"};
  using Reply = LineReply<kMaxReplyLength>;

  /// One row of the command table (seed_session.cpp); docs/protocols/seed.md
  /// is checked against these rows (tests/docs).
  struct Command {
    std::string_view name;  ///< the letter after '$', case-insensitive
    std::uint8_t args;      ///< comma-separated fields after it; others: SYNTAX
    void (SeedSession::*run)(std::string_view arg, ByteSink& out);
    std::string_view help;
    /// `$ERR,DENIED` to a read-only client (Session::may_control). `$D`
    /// (the stop) is not; `$E` only arms this session.
    bool changes_state;
  };
  static std::span<const Command> commands();

  explicit SeedSession(Controller& controller) : controller_(controller) {}

  void receive(std::string_view bytes, ByteSink& out) override;

  /// Handles one command line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

  bool enabled() const { return enabled_; }

 private:
  static const Command kCommands[];

  void enable(std::string_view arg, ByteSink& out);
  void disable(std::string_view arg, ByteSink& out);
  void speed(std::string_view arg, ByteSink& out);
  void run(std::string_view arg, ByteSink& out);
  void query(std::string_view arg, ByteSink& out);
  void write_state(ByteSink& out);

  Controller& controller_;
  LineAssembler<kMaxLineLength> lines_;
  bool enabled_ = false;
};

}  // namespace rotord::protocol
