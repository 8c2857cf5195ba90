#pragma once
#include <cstdint>
#include <span>

#include "protocol/line_assembler.hpp"
#include "protocol/line_reply.hpp"
#include "protocol/session.hpp"
#include "rotator/client_frame.hpp"

namespace rotord::protocol {

/// Where the monitor lines of every WRC session are copied as well (the Pico
/// W's USB log port, where the WRC firmware prints them): at most one line
/// per monitor period, however many clients have MONITOR on.
class MonitorTap {
 public:
  explicit MonitorTap(ByteSink& sink) : sink_(sink) {}
  void offer(Millis now, std::string_view line);

 private:
  ByteSink& sink_;
  bool written_once_ = false;
  Millis last_write_ = 0;
};

/// The WRC text protocol of the Pico W rotator firmware we started from
/// (webradiocontrol/wrc-rotator-controller): one command per line, replies
/// `OK ...` or `ERROR <REASON>`, CR LF line ends (Arduino println). Extended
/// with EL / EL? for az/el rotators and FAULT? for latched faults.
class WrcSession final : public Session {
 public:
  std::string_view front() const override { return "wrc"; }
  static constexpr std::size_t kMaxLineLength = 128;
  static constexpr std::size_t kMaxReplyLength = 192;
  static constexpr Millis kMonitorPeriodMs = 100;
  static constexpr std::string_view kTooManyConnections = "ERROR TOO MANY CONNECTIONS\r\n";
  /// CR LF lines; a reply that cannot fit is this error (never seen in
  /// practice: every reply is a bounded number or word).
  static constexpr ReplyRules kReplyRules{"\r\n", "ERROR REPLY TOO LONG\r\n"};
  using Reply = LineReply<kMaxReplyLength>;

  /// Whether a command takes an argument after its name.
  enum class Arg : std::uint8_t {
    kNone,      ///< `STOP`: an argument makes the line an invalid command
    kRequired,  ///< `AZ 200`: without one the name is no command (`AZ` alone is invalid)
  };
  /// One row of the command table (wrc_session.cpp): the docs' command list
  /// is checked against these rows (tests/docs).
  struct Command {
    std::string_view name;  ///< matched case-insensitively
    Arg arg;
    void (WrcSession::*run)(std::string_view arg, ByteSink& out);
    std::string_view help;
    /// Moves the rotator or changes a setting: `ERROR NOT ALLOWED` to a
    /// read-only client (Session::may_control), checked before the argument.
    bool changes_state;
  };
  static std::span<const Command> commands();

  WrcSession(Controller& controller, const char* version, MonitorTap* tap = nullptr)
      : controller_(controller), version_(version), tap_(tap) {}

  void receive(std::string_view bytes, ByteSink& out) override;
  void poll(Millis now, ByteSink& out) override;

  /// Handles one command line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

 private:
  static const Command kCommands[];

  /// A STATE line: "OK STATE ..." answers a request, "STATE ..." is pushed.
  void write_state(ByteSink& out, const char* prefix);

  // The handlers of the command table.
  void go_az(std::string_view arg, ByteSink& out);
  void get_az(std::string_view arg, ByteSink& out);
  void go_el(std::string_view arg, ByteSink& out);
  void get_el(std::string_view arg, ByteSink& out);
  void move(std::string_view arg, ByteSink& out);
  void state(std::string_view arg, ByteSink& out);
  void fault(std::string_view arg, ByteSink& out);
  void set_speed(std::string_view arg, ByteSink& out);
  void get_speed(std::string_view arg, ByteSink& out);
  void stop(std::string_view arg, ByteSink& out);
  void park(std::string_view arg, ByteSink& out);
  void reset(std::string_view arg, ByteSink& out);
  void monitor(std::string_view arg, ByteSink& out);
  void info(std::string_view arg, ByteSink& out);
  void az_limits(std::string_view arg, ByteSink& out);
  void set_az_offset(std::string_view arg, ByteSink& out);
  void get_az_offset(std::string_view arg, ByteSink& out);

  Controller& controller_;
  ClientFrame frame_;  // the azimuth frame this client sends in
  const char* version_;
  MonitorTap* tap_;
  LineAssembler<kMaxLineLength> lines_;
  bool monitor_ = false;
  // MONITOR's period runs on the transport's clock (poll's `now`), not on
  // controller time, which `rotord --speedup N` makes N times faster.
  Millis now_ = 0;
  Millis last_push_ = 0;
};

}  // namespace rotord::protocol
