#pragma once
#include "protocol/line_assembler.hpp"
#include "protocol/session.hpp"

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
  static constexpr std::size_t kMaxLineLength = 128;
  static constexpr Millis kMonitorPeriodMs = 100;
  static constexpr std::string_view kTooManyConnections = "ERROR TOO MANY CONNECTIONS\r\n";

  WrcSession(Controller& controller, const char* version, MonitorTap* tap = nullptr)
      : controller_(controller), version_(version), tap_(tap) {}

  void receive(std::string_view bytes, ByteSink& out) override;
  void poll(Millis now, ByteSink& out) override;

  /// Handles one command line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

 private:
  /// A STATE line: "OK STATE ..." answers a request, "STATE ..." is pushed.
  void write_state(ByteSink& out, const char* prefix);

  Controller& controller_;
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
