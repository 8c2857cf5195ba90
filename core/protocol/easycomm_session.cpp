#include "protocol/easycomm_session.hpp"
#include "protocol/easycomm_tokens.hpp"

#include <array>
#include <cmath>
#include <cstdio>

#include "command/settings_commands.hpp"
#include "command/typed.hpp"
#include "motion/angles.hpp"
#include "protocol/alarm_word.hpp"
#include "protocol/reading_format.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using easycomm::all_letters;
using easycomm::is_velocity;
using easycomm::next_token;
using easycomm::starts_with;

using settings::Id;

/// One reply line, LF ended, in one write.
template <typename... Args>
void send(ByteSink& out, const char* fmt, Args... args) {
  EasycommSession::Reply(EasycommSession::kReplyRules).line(out, fmt, args...);
}

/// The alarm line: Easycomm's only way to report a problem (`ALxxx`).
void alarm(ByteSink& out, const char* reason) {
  send(out, "AL%s", reason);
}

/// Easycomm adds UNKNOWN for a command it does not know.
const char* alarm_reason(Error e) {
  return e == Error::kNotFound ? "UNKNOWN" : alarm_word(e);
}

/// Bare words that are commands (the rows that take no value), so an
/// Easycomm I mode field never hides one.
bool is_bare_command(std::string_view token) {
  for (const EasycommSession::Command& c : EasycommSession::commands()) {
    using Arg = EasycommSession::Arg;
    const bool bare = c.arg == Arg::kWord || c.arg == Arg::kNone || c.arg == Arg::kQueryOrNumber;
    if (bare && text::iequals(token, c.name)) return true;
  }
  return false;
}

/// Easycomm III registers that are not settings keys: `0` is the proposed
/// MaxSpeed register; `7`/`8` are the SatNOGS firmware's park registers.
std::optional<Id> find_register(std::string_view reg) {
  if (reg == "0") return Id::kSpeedPct;
  if (reg == "7") return Id::kParkAzDeg;
  if (reg == "8") return Id::kParkElDeg;
  return settings::find(reg);
}

}  // namespace

void EasycommSession::receive(std::string_view bytes, ByteSink& out) {
  lines_.feed(bytes, [&](std::string_view line, bool overflowed) {
    if (overflowed) {
      alarm(out, "OVERFLOW");
      return;
    }
    handle_line(line, out);
  });
}

void EasycommSession::handle_line(std::string_view line, ByteSink& out) {
  // Every token is checked before anything runs, so a line with one bad
  // token moves nothing.
  LineRequest request;
  {
    std::string_view rest = line;
    bool any = false;
    bool only_stops = true;
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (!parse_token(token, rest, request, out)) return;
      any = true;
      only_stops = only_stops && (text::iequals(token, "SA") || text::iequals(token, "SE"));
    }
    if (any && !command_arrives(only_stops)) return;
  }
  std::string_view rest = line;
  for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest))
    run_token(token, rest, out);
  finish_line(request, out);
}

// The command table, in the order of docs/protocols/easycomm.md.
using C = EasycommSession;
using A = EasycommSession::Arg;
constexpr EasycommSession::Command EasycommSession::kCommands[] = {
    {"AZ", A::kQueryOrNumber, nullptr, &LineRequest::query_az, &LineRequest::set_az_deg,
     "AZ: azimuth query; AZx.x: go to (one go-to with ELy.y on the line)", true},
    {"EL", A::kQueryOrNumber, nullptr, &LineRequest::query_el, &LineRequest::set_el_deg,
     "EL: elevation query; ELy.y: go to", true},
    {"SA", A::kNone, nullptr, &LineRequest::stop_az, nullptr, "SA: stop azimuth", false},
    {"SE", A::kNone, nullptr, &LineRequest::stop_el, nullptr, "SE: stop elevation", false},
    {"ML", A::kNone, &C::move_left, nullptr, nullptr, "ML: move left (CCW)", true},
    {"MR", A::kNone, &C::move_right, nullptr, nullptr, "MR: move right (CW)", true},
    {"MU", A::kNone, &C::move_up, nullptr, nullptr, "MU: move up", true},
    {"MD", A::kNone, &C::move_down, nullptr, nullptr, "MD: move down", true},
    {"VL", A::kVelocity, &C::move_left, nullptr, nullptr, "VLn: move left at n mdeg/s", true},
    {"VR", A::kVelocity, &C::move_right, nullptr, nullptr, "VRn: move right at n mdeg/s", true},
    {"VU", A::kVelocity, &C::move_up, nullptr, nullptr, "VUn: move up at n mdeg/s", true},
    {"VD", A::kVelocity, &C::move_down, nullptr, nullptr, "VDn: move down at n mdeg/s", true},
    {"PARK", A::kWord, &C::park, nullptr, nullptr, "PARK: go to the park position", true},
    {"RESET", A::kWord, &C::reset, nullptr, nullptr, "RESET: stop, clear faults", true},
    {"VE", A::kNone, &C::version, nullptr, nullptr, "VE: version", false},
    {"GS", A::kNone, &C::status, nullptr, nullptr, "GS: status register", false},
    {"GE", A::kNone, &C::errors, nullptr, nullptr, "GE: error register", false},
    {"CR", A::kRegister, &C::read_config, nullptr, nullptr, "CRr: read configuration register r",
     false},
    {"CW", A::kRegister, &C::write_config, nullptr, nullptr,
     "CWr,value: write configuration register r", true},
    // Radio, time and AOS/LOS fields concern no rotator: checked, ignored.
    {"UP", A::kFrequency, nullptr, nullptr, nullptr, "UPn [mode]: uplink (ignored)", false},
    {"DN", A::kFrequency, nullptr, nullptr, nullptr, "DNn [mode]: downlink (ignored)", false},
    {"UM", A::kAny, nullptr, nullptr, nullptr, "UMx: uplink mode (ignored)", false},
    {"DM", A::kAny, nullptr, nullptr, nullptr, "DMx: downlink mode (ignored)", false},
    {"UR", A::kAny, nullptr, nullptr, nullptr, "URn: uplink radio (ignored)", false},
    {"DR", A::kAny, nullptr, nullptr, nullptr, "DRn: downlink radio (ignored)", false},
    {"ST", A::kAny, nullptr, nullptr, nullptr, "STtime: set time (ignored)", false},
    {"AO", A::kNone, nullptr, nullptr, nullptr, "AO: acquisition of signal (ignored)", false},
    {"LO", A::kNone, nullptr, nullptr, nullptr, "LO: loss of signal (ignored)", false},
    // Digital/analogue I/O channels: this controller has none to offer.
    {"IP", A::kAny, &C::io_channel, nullptr, nullptr, "IPn: digital input (unsupported)", false},
    {"OP", A::kAny, &C::io_channel, nullptr, nullptr, "OPn: digital output (unsupported)", false},
    {"AN", A::kAny, &C::io_channel, nullptr, nullptr, "ANn: analogue input (unsupported)", false},
};

std::span<const EasycommSession::Command> EasycommSession::commands() {
  return kCommands;
}

const EasycommSession::Command* EasycommSession::find(std::string_view token) {
  for (const Command& c : kCommands) {
    if (c.arg == Arg::kWord ? text::iequals(token, c.name) : starts_with(token, c.name)) return &c;
  }
  return nullptr;
}

bool EasycommSession::parse_token(std::string_view token, std::string_view& rest,
                                  LineRequest& request, ByteSink& out) {
  auto reject = [&](const char* reason) {
    alarm(out, reason);
    return false;
  };
  const Command* c = find(token);
  if (c == nullptr) return reject("UNKNOWN");
  const std::string_view value = text::slice(token, c->name.size());
  switch (c->arg) {
    case Arg::kWord:
    case Arg::kAny:
      return true;
    case Arg::kNone:
      if (!value.empty()) return reject("SYNTAX");
      if (c->flag != nullptr) request.*(c->flag) = true;
      return true;
    case Arg::kQueryOrNumber: {
      if (value.empty()) return request.*(c->flag) = true;
      double deg = 0;
      if (!text::parse_double(value, deg)) return reject("SYNTAX");
      request.*(c->target) = static_cast<float>(deg);
      return true;
    }
    case Arg::kVelocity:
      return is_velocity(value) || reject("SYNTAX");
    case Arg::kRegister:
      // The register may follow as its own token ("CR 1", as Hamlib writes it).
      if (value.empty() && next_token(rest).empty()) return reject("SYNTAX");
      return true;
    case Arg::kFrequency: {
      // Easycomm I: "UP000 XXX" -- a frequency, then a mode word.
      std::string_view peek = rest;
      const std::string_view mode = next_token(peek);
      if (all_letters(mode) && !is_bare_command(mode)) rest = peek;
      return true;
    }
  }
  return reject("UNKNOWN");
}

void EasycommSession::run_token(std::string_view token, std::string_view& rest, ByteSink& out) {
  const Command* c = find(token);  // checked by parse_token
  if (c == nullptr) return;
  std::string_view value = text::slice(token, c->name.size());
  // Take the same tokens parse_token took: a register on its own, the mode
  // word after a frequency.
  if (c->arg == Arg::kRegister && value.empty()) value = next_token(rest);
  if (c->arg == Arg::kFrequency) {
    std::string_view peek = rest;
    const std::string_view mode = next_token(peek);
    if (all_letters(mode) && !is_bare_command(mode)) rest = peek;
  }
  // AZ/EL/SA/SE are collected for finish_line, which refuses a position.
  if (c->run == nullptr) return;
  if (c->changes_state && !may_control(controller_, c->name)) return alarm(out, "DENIED");
  (this->*(c->run))(value, out);
}

void EasycommSession::park(std::string_view, ByteSink& out) {
  const Error e = command::park(controller_, origin());
  if (e != Error::kOk) alarm(out, alarm_reason(e));
}

void EasycommSession::reset(std::string_view, ByteSink& out) {
  if (command::reset(controller_, origin()) != Error::kOk) alarm(out, "ESTOP");
}

void EasycommSession::move_left(std::string_view velocity, ByteSink& out) {
  move(AxisId::kAz, Direction::kCcw, velocity, out);
}

void EasycommSession::move_right(std::string_view velocity, ByteSink& out) {
  move(AxisId::kAz, Direction::kCw, velocity, out);
}

void EasycommSession::move_up(std::string_view velocity, ByteSink& out) {
  move(AxisId::kEl, Direction::kCw, velocity, out);
}

void EasycommSession::move_down(std::string_view velocity, ByteSink& out) {
  move(AxisId::kEl, Direction::kCcw, velocity, out);
}

void EasycommSession::version(std::string_view, ByteSink& out) {
  send(out, "VErotord-%s", version_);
}

void EasycommSession::status(std::string_view, ByteSink& out) {
  send(out, "GS%d", status_register());
}

void EasycommSession::errors(std::string_view, ByteSink& out) {
  send(out, "GE%d", error_register());
}

void EasycommSession::io_channel(std::string_view, ByteSink& out) {
  alarm(out, "UNSUPPORTED");
}

void EasycommSession::move(AxisId axis, Direction dir, std::string_view velocity, ByteSink& out) {
  int speed_pct = -1;
  if (!velocity.empty()) {
    long mdeg_s = 0;
    text::parse_int(velocity, mdeg_s);  // checked in parse_token
    speed_pct = speed_pct_from_velocity(mdeg_s);
  }
  const Error e = command::move(controller_, origin(), axis, dir, speed_pct);
  if (e != Error::kOk) alarm(out, alarm_reason(e));
}

void EasycommSession::read_config(std::string_view reg, ByteSink& out) {
  const std::optional<Id> id = find_register(reg);
  if (!id) return alarm(out, "UNKNOWN");
  char value[settings::kValueTextCapacity];
  const std::size_t n = controller_.settings().format_value(*id, value, sizeof(value));
  send(out, "CR%.*s,%.*s", static_cast<int>(reg.size()), reg.data(), static_cast<int>(n), value);
}

void EasycommSession::write_config(std::string_view arg, ByteSink& out) {
  const std::size_t comma = arg.find(',');
  if (comma == std::string_view::npos) return alarm(out, "SYNTAX");
  const std::optional<Id> id = find_register(text::slice(arg, 0, comma));
  if (!id) return alarm(out, "UNKNOWN");
  // The command layer's settings write: never a secret or an access rule
  // (written through the web or REST only); a value that breaks a
  // cross-setting rule (a min above its max) is undone.
  const command::SetResult r = command::set_setting(
      controller_, origin(), command::Writer::kNetwork, *id, text::slice(arg, comma + 1));
  if (r.status == command::SetResult::kRefused) return alarm(out, "DENIED");
  if (r.status != command::SetResult::kOk) alarm(out, "RANGE");
}

void EasycommSession::finish_line(const LineRequest& request, ByteSink& out) {
  if (request.stop_az && request.stop_el) {
    command::stop(controller_, origin());
  } else if (request.stop_az || request.stop_el) {
    // An elevation stop on an azimuth-only rotator does nothing.
    command::stop_axis(controller_, origin(), request.stop_az ? AxisId::kAz : AxisId::kEl);
  }
  if ((request.set_az_deg || request.set_el_deg) && !may_control(controller_, "goto")) {
    alarm(out, "DENIED");
  } else if (request.set_az_deg || request.set_el_deg) {
    std::optional<float> el = request.set_el_deg;
    // An azimuth-only rotator ignores the elevation field Hamlib always sends.
    if (!controller_.has_el()) el.reset();
    if (request.set_az_deg || el) {
      // 0..360 is a compass bearing; the controller picks the turn within
      // the overlap. Beyond 0..360 it is an unwrapped position, refused
      // unless inside the travel.
      const Error e = command::go_to(controller_, origin(), request.set_az_deg, el,
                                     AzTarget::kCompass, source());
      if (e != Error::kOk) alarm(out, alarm_reason(e));
      if (e == Error::kOk && request.set_az_deg)
        frame_.note_goto(*request.set_az_deg, controller_.az_continuity_shift_deg(),
                         controller_.last_goto_recognised(), el ? *el : 0.0f);
    }
  }
  if (!request.query_az && !request.query_el) return;
  RotatorStatus s = controller_.status();
  // A recognised flip pass reads in the flip frame the client sent.
  frame_.read(s.az.position_deg, s.el.position_deg, controller_.recognised_az_deg());
  // Easycomm reports a compass bearing: Hamlib's 0..360 limits and trackers
  // comparing it with the bearing they sent expect one, whatever the cable
  // wrap (the unwrapped position is on the web page, rotctld and WRC).
  const double az = bearing_rounded(s.az.position_deg, 1);
  const double el = s.el.present ? one_decimal(s.el.position_deg) : 0.0;
  if (request.query_az && request.query_el) return send(out, "AZ%.1f EL%.1f", az, el);
  if (request.query_az) return send(out, "AZ%.1f", az);
  send(out, "EL%.1f", el);
}

int EasycommSession::status_register() const {
  // Easycomm III GS bits: 1 idle, 2 moving, 4 pointing (at the target), 8 error.
  const RotatorStatus s = controller_.status();
  int bits = 0;
  if (s.moving()) {
    bits |= 2;
  } else if (s.az.arrived || (s.el.present && s.el.arrived)) {  // the last go-to got there
    bits |= 4;
  } else {
    bits |= 1;
  }
  if (s.any_fault()) bits |= 8;
  return bits;
}

int EasycommSession::error_register() const {
  // Easycomm III GE bits: 1 sensor error, 2 jam, 4 homing error (no homing
  // here). A move timeout is reported as a jam: the drive ran, the antenna
  // did not get there.
  const RotatorStatus s = controller_.status();
  int bits = 0;
  for (const AxisStatus* a : {&s.az, &s.el}) {
    switch (a->fault) {
      case AxisFault::kNone:
        break;
      case AxisFault::kStall:
      case AxisFault::kTimeout:
        bits |= 2;
        break;
      default:
        bits |= 1;
        break;
    }
  }
  return bits;
}

}  // namespace rotord::protocol
