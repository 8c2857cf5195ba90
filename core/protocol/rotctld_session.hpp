#pragma once
#include <array>
#include <cstdint>

#include "protocol/rotctld_commands.hpp"
#include "protocol/rotctld_reply.hpp"
#include "protocol/session.hpp"
#include "rotator/client_frame.hpp"
#include "tracking/track_plan.hpp"

namespace rotord {
using Limits = tracking::Travel;  // rotator/controller.hpp
}

namespace rotord::protocol {

/// Hamlib's rotctld TCP protocol, byte-compatible with `rotctld` 4.5.4 (see
/// docs/protocols/rotctld.md). Like rotctld it reads a character stream, not
/// lines: a command is one character or `\long_name`, its arguments are the
/// next whitespace-separated tokens wherever the line ends fall, and an
/// optional `+` or punctuation prefix selects the Extended Response Protocol.
/// Set commands answer `RPRT 0`, get commands their values only, failures
/// `RPRT -n` with Hamlib's error codes. Each reply is one ByteSink::write.
/// Deviation: an unknown command is answered with `RPRT -4` (RIG_ENIMPL) and
/// the rest of its line is skipped; rotctld stays silent, which would hang a
/// client waiting for an answer.
class RotctldSession final : public Session {
 public:
  std::string_view front() const override { return "rotctld"; }
  static constexpr std::size_t kMaxNameLength = 32;  ///< Hamlib MAXNAMSIZ
  static constexpr std::size_t kMaxArgLength = 127;  ///< Hamlib MAXARGSZ
  static constexpr std::size_t kMaxArgs = 4;
  /// A send_cmd line is read with fgets(MAXARGSZ): at most 126 characters.
  static constexpr std::size_t kMaxLineArgLength = 126;
  static constexpr std::size_t kPauseInputBytes = 512;  ///< input held during \pause
  static constexpr long kMaxPauseS = 60;
  /// rotctld's \dump_state sends its backend's model number; no client uses
  /// it (netrotctl reads and drops the line). 1 is Hamlib's dummy rotator, a
  /// rotctld with no Hamlib backend behind it, and keeps our dump_state
  /// byte-identical to `rotctld -m 1` when the limits agree.
  static constexpr int kModelNumber = 1;
  /// Sent to a client beyond net.max_clients before the close: model 2 reads
  /// it as a failed open ("Command rejected by the rig"), Gpredict as an error.
  static constexpr std::string_view kTooManyConnections = "RPRT -9\n";

  RotctldSession(Controller& controller, const char* version)
      : controller_(controller), version_(version) {}

  void receive(std::string_view bytes, ByteSink& out) override;
  /// Ends a \pause when its time has come and runs the input held meanwhile.
  void poll(Millis now, ByteSink& out) override;
  bool wants_close() const override { return state_ == State::kClosed; }

  /// The limits \dump_state reports and set_pos enforces. An azimuth-only
  /// rotator reports (and accepts, then ignores) elevations 0..90, because
  /// Gpredict and SatNOGS send an elevation anyway and Hamlib's model 2
  /// refuses it locally when max_el is 0.
  static Limits reported_limits(const Controller& controller);

 private:
  enum class State : std::uint8_t {
    kCommand,         ///< before a command: skips line ends and blanks
    kAfterPlus,       ///< '+' seen: a separator character may follow
    kAfterSeparator,  ///< ERP prefix complete: the command character follows
    kLongName,        ///< after '\': letters, digits and '_'
    kComment,         ///< '#' up to the line end
    kArguments,       ///< reading whitespace-separated tokens
    kLineArgument,    ///< send_cmd: the rest of the line
    kDiscardLine,     ///< after an unknown command, up to the line end
    kClosed,          ///< `q` seen: nothing more is read
  };

  void consume(std::string_view bytes, ByteSink& out);
  void feed(char c, ByteSink& out);
  void command_char(char c, ByteSink& out);
  void finish_long_name(char terminator, ByteSink& out);
  void begin(const rotctld::Command& command, ByteSink& out);
  void argument_char(char c, ByteSink& out);
  void line_char(char c, ByteSink& out);
  void unknown(ByteSink& out, bool line_ended);
  void run(ByteSink& out);
  void end_command();

  std::string_view arg(std::size_t i) const;
  /// Runs the command (rotctld_handlers.cpp); values go to reply_ only once
  /// every check has passed, so a failure leaves nothing but the echo.
  rotctld::HamlibError execute(const rotctld::Command& command);
  /// One returned value: `Label: ` in extended mode, then the value and the
  /// separator, as rotctld's get_pos/get_info/get_status print them.
  template <typename... Args>
  void value(const char* label, const char* fmt, Args... args);
  rotctld::HamlibError set_conf(std::string_view token, std::string_view text);
  rotctld::HamlibError get_conf(std::string_view token);
  // The commands with more to them than a line (rotctld_handlers.cpp).
  rotctld::HamlibError set_pos();
  rotctld::HamlibError get_pos();
  /// No functions or parameters: the answers rotctld gives for an unknown one.
  rotctld::HamlibError func_or_parm(rotctld::Op op);
  rotctld::HamlibError set_level();
  rotctld::HamlibError get_level();
  rotctld::HamlibError pause();
  rotctld::HamlibError move(std::string_view direction, std::string_view speed);
  void status_flags();
  void dump_state();
  void dump_caps();
  rotctld::HamlibError locator_helper(rotctld::Op op);
  /// The degrees/minutes/seconds helpers (dms2dec and the like).
  rotctld::HamlibError angle_helper(rotctld::Op op);

  Controller& controller_;
  ClientFrame frame_;  // the azimuth frame this client sends in
  const char* version_;
  State state_ = State::kCommand;
  bool extended_ = false;
  char separator_ = '\n';

  std::array<char, kMaxNameLength> name_{};
  std::size_t name_length_ = 0;
  bool name_too_long_ = false;

  const rotctld::Command* command_ = nullptr;
  std::array<char, kMaxArgs * kMaxArgLength> args_{};
  std::array<std::uint16_t, kMaxArgs> arg_start_{};
  std::array<std::uint16_t, kMaxArgs> arg_length_{};
  std::size_t arg_count_ = 0;
  std::size_t args_used_ = 0;
  bool in_token_ = false;
  bool arg_too_long_ = false;
  bool line_skipped_lf_ = false;

  bool paused_ = false;
  /// A \pause's length until the next poll() starts it: the session knows
  /// the transport's time only from poll(), and on a fresh connection the
  /// command arrives before the first one.
  Millis pause_ms_ = 0;
  bool pause_started_ = false;
  Millis pause_until_ = 0;  // on the transport's clock
  std::array<char, kPauseInputBytes> pause_input_{};
  std::size_t pause_input_length_ = 0;

  rotctld::ReplyBuffer reply_{rotctld::kReplyRules};
};

template <typename... Args>
inline void RotctldSession::value(const char* label, const char* fmt, Args... args) {
  if (extended_) reply_.format("%s: ", label);
  reply_.format(fmt, args...);
  reply_.put(separator_);
}

}  // namespace rotord::protocol
