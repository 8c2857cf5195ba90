#include "protocol/easycomm_session.hpp"

#include <array>
#include <cmath>
#include <cstdio>

#include "motion/angles.hpp"
#include "protocol/reading_format.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

/// Formats one reply line into a fixed buffer and writes it with LF (Hamlib
/// reads up to LF; a CR alone makes it time out).
void send(ByteSink& out, const char* fmt, auto... args) {
  char buf[EasycommSession::kMaxReplyLength];
  const int n = std::snprintf(buf, sizeof(buf) - 1, fmt, args...);
  if (n < 0) return;
  std::size_t len =
      static_cast<std::size_t>(n) < sizeof(buf) - 1 ? static_cast<std::size_t>(n) : sizeof(buf) - 2;
  buf[len++] = '\n';
  out.write(std::string_view(buf, len));
}

/// The alarm line: Easycomm's only way to report a problem (`ALxxx`).
void alarm(ByteSink& out, const char* reason) {
  send(out, "AL%s", reason);
}

const char* alarm_reason(Error e) {
  switch (e) {
    case Error::kOutOfRange:
      return "RANGE";
    case Error::kFaulted:
      return "FAULT";
    case Error::kLimit:
      return "LIMIT";
    case Error::kNotSupported:
      return "UNSUPPORTED";
    case Error::kNotFound:
      return "UNKNOWN";
    default:
      return "SYNTAX";
  }
}

bool is_separator(char c) {
  // ';' because Hamlib 4.5.4 sends "GS\n;" and the ';' opens the next line.
  return c == ' ' || c == '\t' || c == ';';
}

std::string_view next_token(std::string_view& rest) {
  std::size_t i = 0;
  while (i < rest.size() && is_separator(rest[i])) ++i;
  std::size_t j = i;
  while (j < rest.size() && !is_separator(rest[j])) ++j;
  const std::string_view token = text::slice(rest, i, j - i);
  rest.remove_prefix(j);
  return token;
}

bool starts_with(std::string_view token, std::string_view prefix) {
  return token.size() >= prefix.size() &&
         text::iequals(text::slice(token, 0, prefix.size()), prefix);
}

bool all_letters(std::string_view s) {
  for (char c : s) {
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) return false;
  }
  return !s.empty();
}

/// Bare words that are commands, so an Easycomm I mode field never hides one.
bool is_bare_command(std::string_view token) {
  constexpr std::array<std::string_view, 15> kWords = {"AZ", "EL", "SA", "SE",   "ML",
                                                       "MR", "MU", "MD", "VE",   "GS",
                                                       "GE", "AO", "LO", "PARK", "RESET"};
  for (std::string_view w : kWords) {
    if (text::iequals(token, w)) return true;
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
    for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
      if (!parse_token(token, rest, request, out)) return;
    }
  }
  std::string_view rest = line;
  for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest))
    run_token(token, rest, out);
  finish_line(request, out);
}

bool EasycommSession::parse_token(std::string_view token, std::string_view& rest,
                                  LineRequest& request, ByteSink& out) {
  auto value_of = [&](std::optional<float>& target) {
    const std::string_view value = text::slice(token, 2);
    double deg = 0;
    if (!text::parse_double(value, deg)) return false;
    target = static_cast<float>(deg);
    return true;
  };
  auto bare = [&] { return token.size() == 2; };
  auto reject = [&](const char* reason) {
    alarm(out, reason);
    return false;
  };

  if (text::iequals(token, "PARK") || text::iequals(token, "RESET")) return true;
  if (token.size() < 2) return reject("UNKNOWN");
  if (starts_with(token, "AZ")) {
    if (bare()) return request.query_az = true;
    return value_of(request.set_az_deg) || reject("SYNTAX");
  }
  if (starts_with(token, "EL")) {
    if (bare()) return request.query_el = true;
    return value_of(request.set_el_deg) || reject("SYNTAX");
  }
  if (starts_with(token, "SA")) return bare() ? (request.stop_az = true) : reject("SYNTAX");
  if (starts_with(token, "SE")) return bare() ? (request.stop_el = true) : reject("SYNTAX");
  if (starts_with(token, "ML") || starts_with(token, "MR") || starts_with(token, "MU") ||
      starts_with(token, "MD") || starts_with(token, "VE") || starts_with(token, "GS") ||
      starts_with(token, "GE") || starts_with(token, "AO") || starts_with(token, "LO"))
    return bare() || reject("SYNTAX");
  if (starts_with(token, "VL") || starts_with(token, "VR") || starts_with(token, "VU") ||
      starts_with(token, "VD")) {
    long velocity = 0;
    return (text::parse_int(text::slice(token, 2), velocity) && velocity >= 0) || reject("SYNTAX");
  }
  if (starts_with(token, "CR") || starts_with(token, "CW")) {
    // The register may follow as its own token ("CR 1", as Hamlib writes it).
    if (bare() && next_token(rest).empty()) return reject("SYNTAX");
    return true;
  }
  if (starts_with(token, "UP") || starts_with(token, "DN")) {
    // Easycomm I: "UP000 XXX" -- a frequency, then a mode word.
    std::string_view peek = rest;
    const std::string_view mode = next_token(peek);
    if (all_letters(mode) && !is_bare_command(mode)) rest = peek;
    return true;
  }
  if (starts_with(token, "UM") || starts_with(token, "DM") || starts_with(token, "UR") ||
      starts_with(token, "DR") || starts_with(token, "ST") || starts_with(token, "IP") ||
      starts_with(token, "OP") || starts_with(token, "AN"))
    return true;
  return reject("UNKNOWN");
}

void EasycommSession::run_token(std::string_view token, std::string_view& rest, ByteSink& out) {
  auto is = [&](std::string_view prefix) { return starts_with(token, prefix); };
  const std::string_view value = token.size() > 2 ? text::slice(token, 2) : std::string_view();

  // Moves, park, reset and register writes: refused to a read-only client
  // (access.control_networks) with an alarm. SA and SE (stop) still work.
  const bool changes_state = text::iequals(token, "PARK") || text::iequals(token, "RESET") ||
                             is("ML") || is("MR") || is("MU") || is("MD") || is("VL") || is("VR") ||
                             is("VU") || is("VD") || is("CW");
  if (changes_state && !may_control(controller_)) {
    if (is("CW") && value.empty()) next_token(rest);  // the register, as its own token
    return alarm(out, "DENIED");
  }

  if (text::iequals(token, "PARK")) {
    const Error e = controller_.park();
    if (e != Error::kOk) alarm(out, alarm_reason(e));
    return;
  }
  if (text::iequals(token, "RESET")) {
    if (controller_.reset() != Error::kOk) alarm(out, "ESTOP");
    return;
  }
  if (is("ML")) return move(AxisId::kAz, Direction::kCcw, {}, out);
  if (is("MR")) return move(AxisId::kAz, Direction::kCw, {}, out);
  if (is("MU")) return move(AxisId::kEl, Direction::kCw, {}, out);
  if (is("MD")) return move(AxisId::kEl, Direction::kCcw, {}, out);
  if (is("VL")) return move(AxisId::kAz, Direction::kCcw, value, out);
  if (is("VR")) return move(AxisId::kAz, Direction::kCw, value, out);
  if (is("VU")) return move(AxisId::kEl, Direction::kCw, value, out);
  if (is("VD")) return move(AxisId::kEl, Direction::kCcw, value, out);
  if (is("VE")) return send(out, "VErotord-%s", version_);
  if (is("GS")) return send(out, "GS%d", status_register());
  if (is("GE")) return send(out, "GE%d", error_register());
  if (is("CR")) return read_config(value.empty() ? next_token(rest) : value, out);
  if (is("CW")) return write_config(value.empty() ? next_token(rest) : value, out);
  if (is("UP") || is("DN")) {
    std::string_view peek = rest;
    const std::string_view mode = next_token(peek);
    if (all_letters(mode) && !is_bare_command(mode)) rest = peek;
    return;
  }
  // Digital/analogue I/O channels: this controller has none to offer.
  if (is("IP") || is("OP") || is("AN")) return alarm(out, "UNSUPPORTED");
  // AZ/EL/SA/SE are collected for finish_line; radio, time and AOS/LOS
  // fields (UM, DM, UR, DR, ST, AO, LO) concern no rotator and are ignored.
}

void EasycommSession::move(AxisId axis, Direction dir, std::string_view velocity, ByteSink& out) {
  int speed_pct = -1;
  if (!velocity.empty()) {
    long mdeg_s = 0;
    text::parse_int(velocity, mdeg_s);  // checked in parse_token
    speed_pct = speed_pct_from_velocity(mdeg_s);
  }
  const Error e = controller_.move(axis, dir, speed_pct);
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
  // Secrets and the access rules are written through the web or REST only.
  if (!settings::line_writable(*id)) return alarm(out, "DENIED");
  // A value that breaks a cross-setting rule (a min above its max) is undone.
  if (controller_.settings().update_from_text(*id, text::slice(arg, comma + 1)).error != Error::kOk)
    alarm(out, "RANGE");
}

void EasycommSession::finish_line(const LineRequest& request, ByteSink& out) {
  if (request.stop_az && request.stop_el) {
    controller_.stop();
  } else if (request.stop_az) {
    controller_.move(AxisId::kAz, Direction::kNone);
  } else if (request.stop_el && controller_.has_el()) {
    controller_.move(AxisId::kEl, Direction::kNone);
  }
  if ((request.set_az_deg || request.set_el_deg) && !may_control(controller_)) {
    alarm(out, "DENIED");
  } else if (request.set_az_deg || request.set_el_deg) {
    std::optional<float> el = request.set_el_deg;
    // An azimuth-only rotator ignores the elevation field Hamlib always sends.
    if (!controller_.has_el()) el.reset();
    if (request.set_az_deg || el) {
      // 0..360 is a compass bearing; the controller picks the turn within
      // the overlap. Beyond 0..360 it is an unwrapped position, refused
      // unless inside the travel.
      const Error e = controller_.go_to(request.set_az_deg, el, AzTarget::kCompass);
      if (e != Error::kOk) alarm(out, alarm_reason(e));
    }
  }
  if (!request.query_az && !request.query_el) return;
  const RotatorStatus s = controller_.status();
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
