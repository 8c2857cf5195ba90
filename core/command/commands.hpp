#pragma once
// The command layer (docs/architecture.md): each command the rotator takes
// from a client exists here once, with its argument checks, who may call
// it, the control lock, its errors as values. The front ends (REST, MQTT)
// translate bytes into a Request and the Result back into bytes; they do
// not decide whether a command may run or what it means.
#include <array>
#include <span>
#include <string_view>

#include "access/peer.hpp"
#include "command/result.hpp"
#include "rotator/controller.hpp"

namespace rotord::command {

/// Who may call a command (or a REST route) once access control is on:
/// kPublic anyone (STOP), kRead a login or any token, kControl a login, a
/// control token or the MQTT broker with mqtt.control, kAdmin the web login.
enum class Need : unsigned char { kPublic, kRead, kControl, kAdmin };

/// What a command (or route) needs before it runs.
struct Gate {
  Need need = Need::kControl;
  /// Refused to all but the control lock's holder while it is held.
  bool locked = true;
  /// Changes state: refused (but STOP) while the access settings are unreadable.
  bool changes = true;
};

/// The caller, as its front end vouched for it.
struct Authority {
  /// What the front end's own access control granted (kAdmin when off).
  Need granted = Need::kAdmin;
  /// The caller holds the control lock.
  bool holds_lock = false;
};

/// One command as a front end hands it over.
struct Request {
  Authority who;
  /// Its address: each caller is its own stream for the go-to continuity rule.
  access::Peer peer;
  /// The arguments as JSON ({} when empty): the REST body, the MQTT payload.
  std::string_view body;
  /// The front end, for the log line ("rest", "mqtt"; command_log.hpp);
  /// empty: none (a test's).
  std::string_view front = {};
};

enum class Id : unsigned char { kStop, kGoto, kMove, kPark, kReset, kSpeed, kPlace, kPreset };

class Commands;
/// One row of the command table (commands.cpp).
struct Def {
  Id id;
  std::string_view name;  ///< the MQTT topic's last level, the REST path's
  Gate gate;
  Result (Commands::*run)(const Request& r);
  std::string_view help;
};

class Commands {
 public:
  /// Hold-to-move's dead-man: how long a jog lasts without a renewal.
  static constexpr Millis kDefaultHoldMs = 1000;
  static constexpr Millis kMinHoldMs = 100;
  static constexpr Millis kMaxHoldMs = 10000;

  explicit Commands(Controller& controller) : controller_(controller) {}

  static std::span<const Def> table();
  /// The row of `id` (the table is in the order of Id).
  static const Def& def(Id id);
  /// The row named `name`; nullptr when none.
  static const Def* find(std::string_view name);

  /// Whether `who` may pass `gate` now: the access level, the failed-closed
  /// access settings, the control lock. kOk, or the refusal, which is
  /// logged when `command` names one (the REST route of a command).
  Result admit(const Gate& gate, const Authority& who, const Def* command = nullptr,
               const Request* r = nullptr);
  /// Admits, then runs.
  Result run(Id id, const Request& r);
  /// A command from the MQTT broker, whose payload is `body` (docs/mqtt.md):
  /// STOP always; any other only with mqtt.control on and the broker's
  /// address `broker` in access.control_networks (failed closed while the
  /// access settings are unreadable), else 403 and a DENIED line. The broker
  /// vouches for no login and never holds the control lock.
  Result from_broker(Id id, const access::Peer& broker, std::string_view body);
  /// Runs a command whose gate the front end already passed through admit(),
  /// and writes its log line (command_log.hpp).
  Result execute(Id id, const Request& r);
  /// The log line of `command` from `r` that ended in `result`.
  void told(const Def& command, const Request& r, const Result& result);

  /// STOP's work (the dead-men cleared too), without its log line: the
  /// stop command's (MQTT's refused body runs that command).
  void stop_all();
  // The commands (commands.cpp), each with its argument checks.
  Result stop(const Request& r);
  Result go_to(const Request& r);
  Result move(const Request& r);
  Result park(const Request& r);
  Result reset(const Request& r);
  Result speed(const Request& r);
  Result place(const Request& r);
  Result preset(const Request& r);

  /// Called on every pass of the port's loop with the transport's (wall)
  /// clock: a hold-to-move whose renewals stopped (page closed, network
  /// gone) stops then; the lock's time left is told on this clock.
  void poll(Millis transport_now);
  Millis transport_now() const { return transport_now_; }
  Controller& controller() { return controller_; }
  /// The control lock's refusal: its holder and time left.
  Result locked_refusal() const;

 private:
  /// Hold-to-move's dead-man per axis, on the transport's clock: hold_ms is
  /// the client's time, whatever `--speedup` or `--clock manual` does to
  /// controller time.
  struct DeadMan {
    bool armed = false;
    Millis until = 0;
  };
  void arm_dead_man(AxisId axis, Millis hold_ms);
  Result admit_only(const Gate& gate, const Authority& who) const;

  Controller& controller_;
  Millis transport_now_ = 0;
  std::array<DeadMan, 2> dead_man_{};
};

// The command table: every command a client may send, once. The REST
// routes of the same names (web/web_api.cpp) and the MQTT topics
// cmd/<name> (mqtt/bridge.cpp) take their gate and their help from here.
inline constexpr Gate kGateAnyone{Need::kPublic, false, false};  // STOP: always, for anyone
inline constexpr Gate kGateControl{Need::kControl, true, true};
inline constexpr Def kCommandTable[] = {
    {Id::kStop, "stop", kGateAnyone, &Commands::stop, "stop everything"},
    {Id::kGoto, "goto", kGateControl, &Commands::go_to, "go to az and/or el"},
    {Id::kMove, "move", kGateControl, &Commands::move, "hold-to-move with a dead-man"},
    {Id::kPark, "park", kGateControl, &Commands::park, "go to the park position"},
    {Id::kReset, "reset", kGateControl, &Commands::reset, "stop, clear latched faults"},
    {Id::kSpeed, "speed", kGateControl, &Commands::speed, "speed in %"},
    {Id::kPlace, "place", kGateControl, &Commands::place,
     "turn the beam to a locator or lat/lon, short or long path"},
    {Id::kPreset, "preset", kGateControl, &Commands::preset, "turn the beam to a named heading"},
};

}  // namespace rotord::command
