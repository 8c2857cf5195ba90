// What each rotctld command does on the controller, and the reply text. The
// formats are those of rotctl_parse.c (Hamlib 4.5.4) unless a comment says
// otherwise.
#include <cmath>

#include "command/settings_commands.hpp"
#include "command/typed.hpp"
#include "protocol/reading_format.hpp"
#include "protocol/rotctld_locator.hpp"
#include "protocol/rotctld_number.hpp"
#include "protocol/rotctld_session.hpp"
#include "rotator/controller.hpp"

namespace rotord::protocol {

using rotctld::Command;
using rotctld::HamlibError;
using rotctld::Op;
using settings::Id;

namespace {

// Hamlib's rot_move() directions (include/hamlib/rotator.h).
constexpr long kMoveUp = 2;
constexpr long kMoveDown = 4;
constexpr long kMoveLeft = 8;
constexpr long kMoveRight = 16;
constexpr long kSpeedNoChange = -1;  // ROT_SPEED_NOCHANGE

HamlibError from(Error e) {
  switch (e) {
    case Error::kOk:
      return HamlibError::kOk;
    case Error::kNotSupported:
      return HamlibError::kNotAvailable;
    case Error::kFaulted:
    case Error::kLimit:
    case Error::kBusy:
    case Error::kStowed:
      return HamlibError::kRejected;
    case Error::kStorage:
      return HamlibError::kIo;
    default:
      return HamlibError::kInvalid;
  }
}

bool axis_moving(const AxisStatus& a) {
  return a.present && a.state != AxisState::kIdle && a.state != AxisState::kFault;
}

}  // namespace

Limits RotctldSession::reported_limits(const Controller& controller) {
  Limits l = controller.limits();
  if (!l.has_el) {
    l.el_min_deg = 0.0f;
    l.el_max_deg = 90.0f;
  }
  return l;
}

HamlibError RotctldSession::execute(const Command& command) {
  switch (command.op) {
    case Op::kSetPos:
      return set_pos();
    case Op::kGetPos:
      return get_pos();
    case Op::kPark:
      return from(command::park(controller_, origin()));
    case Op::kStop:
      command::stop(controller_, origin());
      return HamlibError::kOk;
    case Op::kReset: {
      long what = 0;  // ROT_RESET_ALL is 1; any value resets all (refused while e-stopped)
      if (!rotctld::scan_whole_int(arg(0), what)) return HamlibError::kInvalid;
      return from(command::reset(controller_, origin()));
    }
    case Op::kMove:
      return move(arg(0), arg(1));
    case Op::kSetLevel:
      return set_level();
    case Op::kGetLevel:
      return get_level();
    case Op::kSetFunc:
    case Op::kGetFunc:
    case Op::kSetParm:
    case Op::kGetParm:
      return func_or_parm(command.op);
    case Op::kSetConf:
      if (arg(1).empty()) return HamlibError::kInvalid;
      return set_conf(arg(0), arg(1));
    case Op::kGetConf:
      return get_conf(arg(0));
    case Op::kGetInfo:
      value("Info", "rotord %s", version_);
      return HamlibError::kOk;
    case Op::kGetStatus:
      status_flags();
      return HamlibError::kOk;
    case Op::kSendCmd:
      // rotctld writes the text to its backend's serial port; there is none
      // behind this server, and the dummy backend answers the same.
      return HamlibError::kIo;
    case Op::kDumpCaps:
      dump_caps();
      return HamlibError::kOk;
    case Op::kDumpState:
      dump_state();
      return HamlibError::kOk;
    case Op::kDumpConf:
      // Hamlib 4.6's rotctld prints its configuration list on its own
      // standard output (dumpconf_list() -> print_conf_list() writes to
      // stdout, not to the client) and answers the client RPRT 0 alone; so
      // does rotord. `\get_conf ?` lists the tokens to a client.
      return HamlibError::kOk;
    case Op::kPause:
      return pause();
    default:
      return locator_helper(command.op);
  }
}

HamlibError RotctldSession::get_pos() {
  RotatorStatus s = controller_.status();
  if (!s.az.position_valid || (s.el.present && !s.el.position_valid)) return HamlibError::kIo;
  frame_.read(s.az.position_deg, s.el.position_deg,
              controller_.recognised_az_deg());  // as this client sent it
  value("Azimuth", "%.2f", az_reading(s, 2));
  value("Elevation", "%.2f", s.el.present ? two_decimals(s.el.position_deg) : 0.0);
  return HamlibError::kOk;
}

HamlibError RotctldSession::func_or_parm(Op op) {
  // No functions or parameters: "?" lists none, a name is unknown (the
  // codes are rotctld's for an unknown name).
  if (arg(0) == "?") {
    reply_.put('\n');
    return HamlibError::kOk;
  }
  return op == Op::kSetFunc ? HamlibError::kNotAvailable : HamlibError::kInvalid;
}

HamlibError RotctldSession::set_pos() {
  double az = 0;
  double el = 0;
  if (!rotctld::scan_float(arg(0), az) || !rotctld::scan_float(arg(1), el))
    return HamlibError::kInvalid;
  // Checked as rot_set_position() checks against the dump_state limits,
  // in float like Hamlib, so what model 2 accepts we accept.
  const float az_deg = static_cast<float>(az);
  const float el_deg = static_cast<float>(el);
  const Limits l = reported_limits(controller_);
  if (az_deg < l.az_min_deg || az_deg > l.az_max_deg || el_deg < l.el_min_deg ||
      el_deg > l.el_max_deg)
    return HamlibError::kInvalid;
  // Hamlib clients send the position they want, overlap included: 420 on
  // a 450 deg rotator is 420, and 60 is 60 wherever the rotator is;
  // except in a tracker's stream, which the continuity rule keeps on
  // its turn (Gpredict sends 0.5 after 359.5, meaning 360.5).
  std::optional<float> el_target;
  if (controller_.has_el()) el_target = el_deg;
  const Error e =
      command::go_to(controller_, origin(), az_deg, el_target, AzTarget::kUnwrapped, source());
  if (e == Error::kOk)
    frame_.note_goto(az_deg, controller_.az_continuity_shift_deg(),
                     controller_.last_goto_recognised(), el_deg);
  return from(e);
}

HamlibError RotctldSession::set_level() {
  if (arg(0) == "?") {
    reply_.append("SPEED \n");
    return HamlibError::kOk;
  }
  if (arg(0) != "SPEED") return HamlibError::kNotAvailable;  // as rotctld: no such level
  long pct = 0;
  if (!rotctld::scan_whole_int(arg(1), pct)) return HamlibError::kInvalid;
  if (pct < 1 || pct > 100) return HamlibError::kInvalid;
  return from(command::set_speed(controller_, origin(), static_cast<int>(pct)));
}

HamlibError RotctldSession::get_level() {
  if (arg(0) == "?") {
    reply_.append("SPEED \n");
    return HamlibError::kOk;
  }
  if (arg(0) != "SPEED") return HamlibError::kInvalid;
  // Printed "%d\n" even in extended mode, as rotctld does.
  reply_.format("%d\n", controller_.status().speed_pct);
  return HamlibError::kOk;
}

HamlibError RotctldSession::move(std::string_view direction, std::string_view speed) {
  long dir = 0;
  if (direction == "LEFT" || direction == "CCW") {
    dir = kMoveLeft;
  } else if (direction == "RIGHT" || direction == "CW") {
    dir = kMoveRight;
  } else if (direction == "UP") {
    dir = kMoveUp;
  } else if (direction == "DOWN") {
    dir = kMoveDown;
  } else if (!rotctld::scan_whole_int(direction, dir)) {
    return HamlibError::kInvalid;
  }
  long pct = 0;
  if (!rotctld::scan_whole_int(speed, pct)) return HamlibError::kInvalid;
  // Speed 1..100 or "no change"; 0 is refused like Hamlib's GS-232B backend
  // does (the dummy backend takes anything).
  if (pct != kSpeedNoChange && (pct < 1 || pct > 100)) return HamlibError::kInvalid;
  AxisId axis = AxisId::kAz;
  Direction drive = Direction::kNone;
  switch (dir) {
    case kMoveUp:
      axis = AxisId::kEl, drive = Direction::kCw;
      break;
    case kMoveDown:
      axis = AxisId::kEl, drive = Direction::kCcw;
      break;
    case kMoveLeft:
      drive = Direction::kCcw;
      break;
    case kMoveRight:
      drive = Direction::kCw;
      break;
    default:
      return HamlibError::kInvalid;
  }
  return from(command::move(controller_, origin(), axis, drive, static_cast<int>(pct)));
}

void RotctldSession::status_flags() {
  // rot_sprintf_status(): each flag name followed by a blank, in bit order.
  const RotatorStatus s = controller_.status();
  char flags[200];
  std::size_t n = 0;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    for (const char* p = name; *p != '\0' && n + 2 < sizeof(flags); ++p) flags[n++] = *p;
    flags[n++] = ' ';
  };
  const bool az_moving = axis_moving(s.az);
  const bool el_moving = axis_moving(s.el);
  add(az_moving || el_moving, "MOVING");
  add(az_moving, "MOVING_AZ");
  add(az_moving && s.az.drive_dir == Direction::kCcw, "MOVING_LEFT");
  add(az_moving && s.az.drive_dir == Direction::kCw, "MOVING_RIGHT");
  add(el_moving, "MOVING_EL");
  add(el_moving && s.el.drive_dir == Direction::kCw, "MOVING_UP");
  add(el_moving && s.el.drive_dir == Direction::kCcw, "MOVING_DOWN");
  add(s.el.present && s.el.limit_cw, "LIMIT_UP");
  add(s.el.present && s.el.limit_ccw, "LIMIT_DOWN");
  add(s.az.limit_ccw, "LIMIT_LEFT");
  add(s.az.limit_cw, "LIMIT_RIGHT");
  // Overlap: elevation past the zenith (a flip) or below the horizon,
  // azimuth below 0 or beyond 360 (the unwrapped overlap zones). Within the
  // go-to tolerance of 0/90/360 counts as there, so sensor noise at a park
  // position does not make the flags flicker.
  const float az_tol = controller_.settings().f(Id::kAzToleranceDeg);
  const float el_tol = controller_.settings().f(Id::kElToleranceDeg);
  add(s.el.present && s.el.position_deg > 90.0f + el_tol, "OVERLAP_UP");
  add(s.el.present && s.el.position_deg < -el_tol, "OVERLAP_DOWN");
  add(!s.limits.az_continuous && s.az.position_deg < -az_tol, "OVERLAP_LEFT");
  add(!s.limits.az_continuous && s.az.position_deg > 360.0f + az_tol, "OVERLAP_RIGHT");
  value("Status flags", "%.*s", static_cast<int>(n), flags);
}

void RotctldSession::dump_state() {
  const Limits l = reported_limits(controller_);
  const bool labels = extended_;
  auto line = [&](const char* label, const char* tag, const char* fmt, auto v) {
    reply_.append(labels ? label : tag);
    reply_.format(fmt, v);
    reply_.put(separator_);
  };
  line("rotctld Protocol Ver: ", "", "%d", 1);  // ROTCTLD_PROT_VER
  line("Rotor Model: ", "", "%d", kModelNumber);
  if (!labels && controller_.settings().b(Id::kRotctldOldClients)) {
    // Hamlib before 4.5.1 (netrotctl_open) takes atof() of lines 3 to 6 as
    // min_az, max_az, min_el, max_el and leaves the rest unread, to be
    // flushed before its next command; 4.5.1 and later skip lines without a
    // '=' and read the tagged ones below (docs/protocols/rotctld.md).
    reply_.format("%f\n%f\n", static_cast<double>(l.az_min_deg), static_cast<double>(l.az_max_deg));
    reply_.format("%f\n%f\n", static_cast<double>(l.el_min_deg), static_cast<double>(l.el_max_deg));
  }
  line("Minimum Azimuth: ", "min_az=", "%f", static_cast<double>(l.az_min_deg));
  line("Maximum Azimuth: ", "max_az=", "%f", static_cast<double>(l.az_max_deg));
  line("Minimum Elevation: ", "min_el=", "%f", static_cast<double>(l.el_min_deg));
  line("Maximum Elevation: ", "max_el=", "%f", static_cast<double>(l.el_max_deg));
  // The client turns every azimuth by 180 deg when this is 1; never wanted.
  line("South Zero: ", "south_zero=", "%d", 0);
  // The last two records keep their key=value form in extended mode too.
  reply_.format("rot_type=%s", l.has_el ? "AzEl" : "Az");
  reply_.put(separator_);
  reply_.append("done");
  reply_.put(separator_);
}

void RotctldSession::dump_caps() {
  // Free-form text no client parses; the layout of dumpcaps_rot().
  const Limits l = reported_limits(controller_);
  reply_.format("Caps dump for model:\t%d\n", kModelNumber);
  reply_.append("Model name:\t\trotord\nMfg name:\t\trotord\n");
  reply_.format("Backend version:\t%s\n", version_);
  reply_.append("Backend status:\t\tStable\n");
  reply_.format("Rot type:\t\t%s\n", l.has_el ? "Az-El" : "Az");
  reply_.append("Port type:\t\tNone\n");
  reply_.append(
      "Status flags: MOVING MOVING_AZ MOVING_LEFT MOVING_RIGHT MOVING_EL MOVING_UP MOVING_DOWN "
      "LIMIT_UP LIMIT_DOWN LIMIT_LEFT LIMIT_RIGHT OVERLAP_UP OVERLAP_DOWN OVERLAP_LEFT "
      "OVERLAP_RIGHT \n");
  reply_.append("Get functions: \nSet functions: \n");
  reply_.append("Get level: SPEED(1..100/1) \nSet level: SPEED(1..100/1) \n");
  reply_.append("Get parameters: \nSet parameters: \n");
  reply_.format("Min Azimuth:\t\t%.2f\n", static_cast<double>(l.az_min_deg));
  reply_.format("Max Azimuth:\t\t%.2f\n", static_cast<double>(l.az_max_deg));
  reply_.format("Min Elevation:\t\t%.2f\n", static_cast<double>(l.el_min_deg));
  reply_.format("Max Elevation:\t\t%.2f\n", static_cast<double>(l.el_max_deg));
  reply_.append(
      "Can set Conf:\t\tY\nCan get Conf:\t\tY\nCan set Position:\tY\nCan get Position:\tY\n"
      "Can Stop:\t\tY\nCan Park:\t\tY\nCan Reset:\t\tY\nCan Move:\t\tY\nCan get Info:\t\tY\n"
      "Can get Status:\t\tY\nCan set Func:\tN\nCan get Func:\tN\nCan set Level:\tY\n"
      "Can get Level:\tY\nCan set Param:\tN\nCan get Param:\tN\n\n"
      "Overall backend warnings: 0\n");
}

namespace {

/// Hamlib's frontend configuration tokens that map onto this controller.
struct ConfToken {
  const char* name;
  Id id;
};
constexpr ConfToken kConfTokens[] = {
    {"min_az", Id::kAzMinDeg},
    {"max_az", Id::kAzMaxDeg},
    {"min_el", Id::kElMinDeg},
    {"max_el", Id::kElMaxDeg},
};

}  // namespace

HamlibError RotctldSession::set_conf(std::string_view token, std::string_view text) {
  // south_zero is a client-side transformation; only "off" is accepted.
  if (token == "south_zero") {
    long on = 0;
    return rotctld::scan_int(text, on) && on == 0 ? HamlibError::kOk : HamlibError::kInvalid;
  }
  std::optional<Id> id;
  for (const ConfToken& t : kConfTokens) {
    if (token == t.name) id = t.id;
  }
  // Any key of the settings table works too ("C park.az_deg 180").
  if (!id) id = settings::find(token);
  if (!id) return HamlibError::kInvalid;
  // The command layer's settings write: never a secret or an access rule
  // (written through the web or REST only); a value that breaks a
  // cross-setting rule (a minimum above its maximum) is undone.
  const command::SetResult r =
      command::set_setting(controller_, origin(), command::Writer::kNetwork, *id, text);
  if (r.status == command::SetResult::kRefused) return HamlibError::kRejected;
  return r.status == command::SetResult::kOk ? HamlibError::kOk : HamlibError::kInvalid;
}

HamlibError RotctldSession::get_conf(std::string_view token) {
  // Hamlib 4.6: "token=value\n", limits printed "%f".
  if (!token.empty() && token[0] == '?') {
    reply_.append("min_az max_az min_el max_el south_zero \n");
    return HamlibError::kOk;
  }
  const Limits l = reported_limits(controller_);
  const std::string_view name = token;
  auto print = [&](float v) {
    reply_.format("%.*s=%f\n", static_cast<int>(name.size()), name.data(), static_cast<double>(v));
    return HamlibError::kOk;
  };
  if (token == "min_az") return print(l.az_min_deg);
  if (token == "max_az") return print(l.az_max_deg);
  if (token == "min_el") return print(l.el_min_deg);
  if (token == "max_el") return print(l.el_max_deg);
  if (token == "south_zero") {
    reply_.append("south_zero=0\n");
    return HamlibError::kOk;
  }
  const std::optional<Id> id = settings::find(token);
  if (!id) return HamlibError::kInvalid;
  char text[settings::kValueTextCapacity];
  const std::size_t n = controller_.settings().format_value(*id, text, sizeof(text));
  reply_.format("%.*s=%.*s\n", static_cast<int>(name.size()), name.data(), static_cast<int>(n),
                text);
  return HamlibError::kOk;
}

}  // namespace rotord::protocol
