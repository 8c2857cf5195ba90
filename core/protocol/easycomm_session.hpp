#pragma once
#include <cstdint>
#include <optional>
#include <span>

#include "protocol/line_assembler.hpp"
#include "protocol/line_reply.hpp"
#include "protocol/session.hpp"
#include "rotator/client_frame.hpp"
#include "util/axis_id.hpp"
#include "util/direction.hpp"

namespace rotord::protocol {

/// Easycomm I/II/III as Hamlib's backends 201, 202 and 204 speak it (see
/// docs/protocols/easycomm.md). Lines end in CR, LF or CRLF; a line holds
/// commands separated by spaces (or the stray ';' Hamlib 4.5.4 appends to
/// configuration commands). Set, move and stop commands are silent (Hamlib
/// never reads a reply to them); queries answer one line ending in LF.
/// Rejected input is answered with an `AL<REASON>` alarm line, the only error
/// report Easycomm defines, and changes nothing.
class EasycommSession final : public Session {
 public:
  std::string_view front() const override { return "easycomm"; }
  static constexpr std::size_t kMaxLineLength = 128;
  static constexpr std::size_t kMaxReplyLength = 160;
  static constexpr std::string_view kTooManyConnections = "ALBUSY\n";
  /// LF lines (Hamlib reads up to LF; a CR alone makes it time out); a
  /// reply that cannot fit is the overflow alarm.
  static constexpr ReplyRules kReplyRules{"\n", "ALOVERFLOW\n"};
  using Reply = LineReply<kMaxReplyLength>;

  EasycommSession(Controller& controller, const char* version)
      : controller_(controller), version_(version) {}

  void receive(std::string_view bytes, ByteSink& out) override;

  /// Handles one line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

  /// Easycomm III velocities are in mdeg/s, but Hamlib 204 writes
  /// (speed - 1) * 100 for its speed level 1..100, so that is the mapping that
  /// round-trips: 0 -> 1 %, 4900 -> 50 %, 9900 and above -> 100 %.
  static int speed_pct_from_velocity(long mdeg_s) {
    return mdeg_s >= 9900 ? 100 : mdeg_s <= 0 ? 1 : static_cast<int>(mdeg_s / 100) + 1;
  }

 private:
  /// What a line asks for, collected first so `AZx ELy` is one go-to and
  /// `AZ EL` one combined reply (Hamlib 4.5 needs both on one line).
  struct LineRequest {
    std::optional<float> set_az_deg;
    std::optional<float> set_el_deg;
    bool query_az = false;
    bool query_el = false;
    bool stop_az = false;
    bool stop_el = false;
  };

 public:
  /// What may follow a command's two letters in its token.
  enum class Arg : std::uint8_t {
    kWord,           ///< nothing: the token is the whole name (PARK, RESET)
    kNone,           ///< nothing (ML, VE, SA, ...): anything else is ALSYNTAX
    kQueryOrNumber,  ///< AZ / EL: bare queries, a number sets
    kVelocity,       ///< VL..VD: a non-negative whole number (mdeg/s)
    kRegister,       ///< CR / CW: a register, attached or as the next token
    kFrequency,      ///< UP / DN (Easycomm I): anything, then an optional mode word
    kAny,            ///< UM, ST, IP, ...: anything
  };
  /// One row of the command table (easycomm_session.cpp); matched by its
  /// name as the token's prefix (kWord: the whole token), case-insensitive.
  /// docs/protocols/easycomm.md is checked against these rows (tests/docs).
  struct Command {
    std::string_view name;
    Arg arg;
    /// Run once the whole line is checked; nullptr: nothing to run (AZ, EL,
    /// SA and SE are collected into the line's request instead, and radio
    /// fields are ignored).
    void (EasycommSession::*run)(std::string_view value, ByteSink& out);
    /// For AZ/EL/SA/SE: the request flag a bare token sets, and the target
    /// a value sets.
    bool LineRequest::*flag;
    std::optional<float> LineRequest::*target;
    std::string_view help;
    /// Moves the rotator or writes a register: `ALDENIED` to a read-only
    /// client (Session::may_control). A position (AZ/EL with a value) is
    /// refused once for the line's go-to; SA and SE (stop) never.
    bool changes_state;
  };
  static std::span<const Command> commands();

 private:
  static const Command kCommands[];
  static const Command* find(std::string_view token);

  void park(std::string_view value, ByteSink& out);
  void reset(std::string_view value, ByteSink& out);
  void move_left(std::string_view value, ByteSink& out);
  void move_right(std::string_view value, ByteSink& out);
  void move_up(std::string_view value, ByteSink& out);
  void move_down(std::string_view value, ByteSink& out);
  void version(std::string_view value, ByteSink& out);
  void status(std::string_view value, ByteSink& out);
  void errors(std::string_view value, ByteSink& out);
  void io_channel(std::string_view value, ByteSink& out);

  /// Checks one token and notes AZ/EL/SA/SE; false (after an alarm) when it
  /// is malformed. `rest` loses the tokens a command takes as arguments.
  bool parse_token(std::string_view token, std::string_view& rest, LineRequest& request,
                   ByteSink& out);
  /// Runs one checked token (AZ/EL/SA/SE wait for finish_line).
  void run_token(std::string_view token, std::string_view& rest, ByteSink& out);
  void move(AxisId axis, Direction dir, std::string_view velocity, ByteSink& out);
  void read_config(std::string_view reg, ByteSink& out);
  void write_config(std::string_view arg, ByteSink& out);
  void finish_line(const LineRequest& request, ByteSink& out);
  int status_register() const;
  int error_register() const;

  Controller& controller_;
  const char* version_;
  LineAssembler<kMaxLineLength> lines_;
  ClientFrame frame_;  // the frame this client sends in (a recognised flip pass)
};

}  // namespace rotord::protocol
