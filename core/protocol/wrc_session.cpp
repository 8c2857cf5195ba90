#include "protocol/wrc_session.hpp"

#include <cstdio>

#include "command/typed.hpp"
#include "protocol/alarm_word.hpp"
#include "protocol/reading_format.hpp"
#include "rotator/controller.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

/// One reply line, CR LF ended, in one write.
template <typename... Args>
void send(ByteSink& out, const char* fmt, Args... args) {
  WrcSession::Reply(WrcSession::kReplyRules).line(out, fmt, args...);
}

/// WRC's `ERROR <REASON>` (docs/protocols/wrc.md): FAULT, LIMIT, STOWED,
/// NOT SUPPORTED, and INVALID ARGUMENT for the rest, out of range included.
const char* error_reason(Error e) {
  return refusal_word(e, {"INVALID ARGUMENT", "NOT SUPPORTED", "INVALID ARGUMENT"});
}

bool parse_float(std::string_view s, float& out) {
  double d = 0;
  if (!text::parse_double(text::trim(s), d)) return false;
  out = static_cast<float>(d);
  return true;
}

}  // namespace

// The command table: one row per command. Names are matched
// case-insensitively; docs/protocols/wrc.md's table is checked
// against these rows (tests/docs/command_docs_test.cpp).
const WrcSession::Command WrcSession::kCommands[] = {
    {"AZ", WrcSession::Arg::kRequired, &WrcSession::go_az,
     "AZ <deg>: turn to an azimuth (compass, or unwrapped 360..max)", true},
    {"AZ?", WrcSession::Arg::kNone, &WrcSession::get_az, "AZ?: the azimuth", false},
    {"EL", WrcSession::Arg::kRequired, &WrcSession::go_el,
     "EL <deg>: turn to an elevation (az/el rotators)", true},
    {"EL?", WrcSession::Arg::kNone, &WrcSession::get_el, "EL?: the elevation", false},
    {"MOVE", WrcSession::Arg::kRequired, &WrcSession::move,
     "MOVE CW|CCW|UP|DOWN: turn until STOP or a limit", true},
    {"STATE", WrcSession::Arg::kNone, &WrcSession::state, "STATE: position, speed and flags",
     false},
    {"FAULT?", WrcSession::Arg::kNone, &WrcSession::fault, "FAULT?: latched faults per axis",
     false},
    {"SPEED", WrcSession::Arg::kRequired, &WrcSession::set_speed, "SPEED <1..100>: speed in %",
     true},
    {"SPEED?", WrcSession::Arg::kNone, &WrcSession::get_speed, "SPEED?: the speed in %", false},
    // STOP works for everyone, always.
    {"STOP", WrcSession::Arg::kNone, &WrcSession::stop, "STOP: stop both axes", false},
    {"PARK", WrcSession::Arg::kNone, &WrcSession::park, "PARK: go to the park position", true},
    {"RESET", WrcSession::Arg::kNone, &WrcSession::reset,
     "RESET: stop, clear latched faults, default speed", true},
    {"MONITOR", WrcSession::Arg::kRequired, &WrcSession::monitor,
     "MONITOR 1|0: push a STATE line every 100 ms", false},
    {"INFO", WrcSession::Arg::kNone, &WrcSession::info, "INFO: name and version", false},
    {"AZLIMITS?", WrcSession::Arg::kNone, &WrcSession::az_limits, "AZLIMITS?: the azimuth travel",
     false},
    {"AZOFFSET", WrcSession::Arg::kRequired, &WrcSession::set_az_offset,
     "AZOFFSET <deg>: azimuth offset, saved", true},
    {"AZOFFSET?", WrcSession::Arg::kNone, &WrcSession::get_az_offset,
     "AZOFFSET?: the azimuth offset", false},
};

std::span<const WrcSession::Command> WrcSession::commands() {
  return kCommands;
}

void WrcSession::receive(std::string_view bytes, ByteSink& out) {
  lines_.feed(bytes, [&](std::string_view line, bool overflowed) {
    if (overflowed) {
      send(out, "ERROR COMMAND TOO LONG");
      return;
    }
    handle_line(line, out);
  });
}

void WrcSession::poll(Millis now, ByteSink& out) {
  now_ = now;
  if (!monitor_ || now - last_push_ < kMonitorPeriodMs) return;
  last_push_ = now;
  // The WRC firmware pushes its monitor lines without the "OK " of a reply.
  if (tap_ == nullptr) return write_state(out, "STATE");
  // The firmware also prints them on its USB log port: one copy of the
  // line goes there as well.
  struct Tee final : ByteSink {
    ByteSink& client;
    MonitorTap& tap;
    Millis now;
    Tee(ByteSink& c, MonitorTap& t, Millis n) : client(c), tap(t), now(n) {}
    void write(std::string_view bytes) override {
      client.write(bytes);
      tap.offer(now, bytes);
    }
  } tee(out, *tap_, now);
  write_state(tee, "STATE");
}

void MonitorTap::offer(Millis now, std::string_view line) {
  if (written_once_ && now - last_write_ < WrcSession::kMonitorPeriodMs) return;
  written_once_ = true;
  last_write_ = now;
  sink_.write(line);
}

void WrcSession::write_state(ByteSink& out, const char* prefix) {
  RotatorStatus s = controller_.status();
  s.az.position_deg = frame_.az_deg(s.az.position_deg);  // as this client sent it
  char flags[64] = "";
  std::size_t n = 0;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    int w = std::snprintf(flags + n, sizeof(flags) - n, "%s%s", n ? "," : "", name);
    if (w > 0 && n + static_cast<std::size_t>(w) < sizeof(flags)) n += static_cast<std::size_t>(w);
  };
  const bool az_driving = s.az.state == AxisState::kStarting || s.az.state == AxisState::kMoving;
  const bool el_driving = s.el.state == AxisState::kStarting || s.el.state == AxisState::kMoving;
  add(az_driving && s.az.drive_dir == Direction::kCw, "CW");
  add(az_driving && s.az.drive_dir == Direction::kCcw, "CCW");
  add(el_driving && s.el.drive_dir == Direction::kCw, "UP");
  add(el_driving && s.el.drive_dir == Direction::kCcw, "DOWN");
  add(s.az.t1, "T1");
  add(s.az.t2, "T2");
  add(s.az.switch_ccw, "L1");
  add(s.az.switch_cw, "L2");
  add(s.any_fault(), "FAULT");
  if (s.el.present) {
    send(out, "%s AZ=%.1f EL=%.1f SPEED=%d FLAGS=%s", prefix, az_reading(s, 1),
         one_decimal(s.el.position_deg), s.speed_pct, flags);
  } else {
    send(out, "%s AZ=%.1f SPEED=%d FLAGS=%s", prefix, az_reading(s, 1), s.speed_pct, flags);
  }
}

void WrcSession::handle_line(std::string_view line, ByteSink& out) {
  line = text::trim(line);
  if (line.empty()) return;
  std::string_view rest = line;
  const std::string_view name = text::next_token(rest);
  const std::string_view arg = text::trim(rest);
  for (const Command& c : kCommands) {
    if (!text::iequals(name, c.name) || (c.arg == Arg::kRequired && arg.empty())) continue;
    if (!command_arrives(c.run == &WrcSession::stop)) return;
    // A read-only client (access.control_networks, the control lock) is
    // refused before its argument is looked at.
    if (c.changes_state && !may_control(controller_, c.name)) return send(out, "ERROR NOT ALLOWED");
    if (c.arg == Arg::kNone && !arg.empty()) break;
    return (this->*c.run)(arg, out);
  }
  send(out, "ERROR INVALID COMMAND");
}

void WrcSession::go_az(std::string_view arg, ByteSink& out) {
  float az = 0;
  if (!parse_float(arg, az)) return send(out, "ERROR INVALID AZIMUTH");
  const Error e =
      command::go_to(controller_, origin(), az, std::nullopt, AzTarget::kCompass, source());
  if (e == Error::kOutOfRange || e == Error::kInvalidArgument)
    return send(out, "ERROR INVALID AZIMUTH");
  if (e == Error::kOk) frame_.note_goto(az, controller_.az_continuity_shift_deg());
  if (e != Error::kOk) return send(out, "ERROR %s", error_reason(e));
  send(out, "OK AZ %.2f", static_cast<double>(az));
}

void WrcSession::get_az(std::string_view, ByteSink& out) {
  RotatorStatus s = controller_.status();
  s.az.position_deg = frame_.az_deg(s.az.position_deg);
  send(out, "OK AZ %.1f", az_reading(s, 1));
}

void WrcSession::go_el(std::string_view arg, ByteSink& out) {
  float el = 0;
  if (!controller_.has_el()) return send(out, "ERROR NOT SUPPORTED");
  if (!parse_float(arg, el)) return send(out, "ERROR INVALID ELEVATION");
  const Error e = command::go_to(controller_, origin(), std::nullopt, el);
  if (e == Error::kOutOfRange || e == Error::kInvalidArgument)
    return send(out, "ERROR INVALID ELEVATION");
  if (e != Error::kOk) return send(out, "ERROR %s", error_reason(e));
  send(out, "OK EL %.2f", static_cast<double>(el));
}

void WrcSession::get_el(std::string_view, ByteSink& out) {
  if (!controller_.has_el()) return send(out, "ERROR NOT SUPPORTED");
  send(out, "OK EL %.1f", one_decimal(controller_.status().el.position_deg));
}

void WrcSession::move(std::string_view arg, ByteSink& out) {
  AxisId axis = AxisId::kAz;
  Direction dir = Direction::kNone;
  if (text::iequals(arg, "CW")) dir = Direction::kCw;
  if (text::iequals(arg, "CCW")) dir = Direction::kCcw;
  if (text::iequals(arg, "UP")) axis = AxisId::kEl, dir = Direction::kCw;
  if (text::iequals(arg, "DOWN")) axis = AxisId::kEl, dir = Direction::kCcw;
  if (dir == Direction::kNone) return send(out, "ERROR INVALID DIRECTION");
  const Error e = command::move(controller_, origin(), axis, dir);
  if (e != Error::kOk) return send(out, "ERROR %s", error_reason(e));
  char upper[8] = {};
  for (std::size_t i = 0; i < arg.size() && i < sizeof(upper) - 1; ++i)
    upper[i] = (arg[i] >= 'a' && arg[i] <= 'z') ? static_cast<char>(arg[i] - 32) : arg[i];
  send(out, "OK MOVE %s", upper);
}

void WrcSession::state(std::string_view, ByteSink& out) {
  write_state(out, "OK STATE");
}

void WrcSession::fault(std::string_view, ByteSink& out) {
  const RotatorStatus s = controller_.status();
  if (s.el.present)
    return send(out, "OK FAULT AZ=%s EL=%s", axis_fault_name(s.az.fault),
                axis_fault_name(s.el.fault));
  send(out, "OK FAULT AZ=%s", axis_fault_name(s.az.fault));
}

void WrcSession::set_speed(std::string_view arg, ByteSink& out) {
  long speed = 0;
  if (!text::parse_int(arg, speed) || speed < 1 || speed > 100)
    return send(out, "ERROR INVALID SPEED");
  command::set_speed(controller_, origin(), static_cast<int>(speed));
  // The WRC firmware prints the speed as an Arduino double: two decimals.
  send(out, "OK SPEED %.2f", static_cast<double>(speed));
}

void WrcSession::get_speed(std::string_view, ByteSink& out) {
  send(out, "OK SPEED %d", controller_.status().speed_pct);
}

void WrcSession::stop(std::string_view, ByteSink& out) {
  command::stop(controller_, origin());
  send(out, "OK STOP");
}

void WrcSession::park(std::string_view, ByteSink& out) {
  const Error e = command::park(controller_, origin());
  if (e != Error::kOk) return send(out, "ERROR %s", error_reason(e));
  send(out, "OK PARK");
}

void WrcSession::reset(std::string_view, ByteSink& out) {
  if (command::reset(controller_, origin()) != Error::kOk) return send(out, "ERROR ESTOP");
  send(out, "OK RESET");
}

void WrcSession::monitor(std::string_view arg, ByteSink& out) {
  long on = 0;
  if (!text::parse_int(arg, on) || (on != 0 && on != 1)) return send(out, "ERROR INVALID ARGUMENT");
  monitor_ = on == 1;
  last_push_ = now_;
  send(out, "OK MONITOR %d", monitor_ ? 1 : 0);
}

void WrcSession::info(std::string_view, ByteSink& out) {
  send(out, "OK INFO rotord %s", version_);
}

void WrcSession::az_limits(std::string_view, ByteSink& out) {
  const Limits l = controller_.limits();
  send(out, "OK AZLIMITS MIN=%g MAX=%g", static_cast<double>(l.az_min_deg),
       static_cast<double>(l.az_max_deg));
}

void WrcSession::set_az_offset(std::string_view arg, ByteSink& out) {
  float offset = 0;
  if (!parse_float(arg, offset)) return send(out, "ERROR INVALID AZIMUTH OFFSET");
  if (controller_.settings().set(Id::kAzOffsetDeg, offset).error != Error::kOk)
    return send(out, "ERROR INVALID AZIMUTH OFFSET");
  send(out, "OK AZOFFSET %.2f", static_cast<double>(offset));
}

void WrcSession::get_az_offset(std::string_view, ByteSink& out) {
  send(out, "OK AZOFFSET %.2f", controller_.settings().get(Id::kAzOffsetDeg));
}

}  // namespace rotord::protocol
