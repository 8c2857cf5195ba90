#include "protocol/seed_session.hpp"

#include <array>
#include <cmath>
#include <cstdio>

#include "protocol/reading_format.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

/// Formats one reply into a fixed buffer and writes it with CR LF, in one unit.
void send(ByteSink& out, const char* fmt, auto... args) {
  char buf[128];
  const int n = std::snprintf(buf, sizeof(buf) - 2, fmt, args...);
  if (n < 0) return;
  std::size_t len =
      static_cast<std::size_t>(n) < sizeof(buf) - 2 ? static_cast<std::size_t>(n) : sizeof(buf) - 3;
  buf[len++] = '\r';
  buf[len++] = '\n';
  out.write(std::string_view(buf, len));
}

/// A fixed reply goes out as it is (never used as a format).
void send(ByteSink& out, const char* line) {
  send(out, "%s", line);
}

void error(ByteSink& out, const char* reason) {
  send(out, "$ERR,%s", reason);
}

const char* error_reason(Error e) {
  switch (e) {
    case Error::kOutOfRange:
      return "RANGE";
    case Error::kFaulted:
      return "FAULT";
    case Error::kLimit:
      return "LIMIT";
    case Error::kNotSupported:
      return "UNSUPPORTED";
    default:
      return "SYNTAX";
  }
}

const char* direction_name(const AxisStatus& a, bool el) {
  const bool driving = a.state == AxisState::kStarting || a.state == AxisState::kMoving;
  if (!a.present || !driving || a.drive_dir == Direction::kNone) return "STOP";
  if (el) return a.drive_dir == Direction::kCw ? "UP" : "DOWN";
  return a.drive_dir == Direction::kCw ? "CW" : "CCW";
}

}  // namespace

void SeedSession::receive(std::string_view bytes, ByteSink& out) {
  lines_.feed(bytes, [&](std::string_view line, bool overflowed) {
    if (overflowed) return error(out, "TOOLONG");
    handle_line(line, out);
  });
}

void SeedSession::handle_line(std::string_view line, ByteSink& out) {
  line = text::trim(line);
  if (line.empty()) return;
  if (line.front() != '$') return error(out, "SYNTAX");
  line.remove_prefix(1);

  // Fields separated by commas; more than kMaxFields is malformed anyway.
  constexpr std::size_t kMaxFields = 3;
  std::array<std::string_view, kMaxFields> fields{};
  std::size_t count = 0;
  for (;;) {
    const std::size_t comma = line.find(',');
    if (count == kMaxFields) return error(out, "SYNTAX");
    fields[count++] = text::trim(text::slice(line, 0, comma));
    if (comma == std::string_view::npos) break;
    line.remove_prefix(comma + 1);
  }
  const std::string_view cmd = fields[0];
  const std::string_view arg = fields[1];
  auto is = [&](const char* name, std::size_t args) {
    return text::iequals(cmd, name) && count == args + 1;
  };
  auto known = [&] {
    for (const char* name : {"E", "D", "S", "R", "Q"}) {
      if (text::iequals(cmd, name)) return true;
    }
    return false;
  };

  if (is("E", 0)) {
    enabled_ = true;
    return send(out, "$OK,E");
  }
  if (is("D", 0)) {
    // Disable is also the stop: every motion ends, whoever started it.
    controller_.stop();
    enabled_ = false;
    return send(out, "$OK,D");
  }
  // Speed and turning: refused to a read-only client (access.control_networks).
  // E only arms this session; D is the stop and always works.
  if ((is("S", 1) || is("R", 1)) && !may_control(controller_)) return error(out, "DENIED");
  if (is("S", 1)) {
    long pct = 0;
    if (!text::parse_int(arg, pct)) return error(out, "SYNTAX");
    if (pct < 1 || pct > 100) return error(out, "RANGE");
    controller_.set_speed_pct(static_cast<int>(pct));
    return send(out, "$OK,S,%ld", pct);
  }
  if (is("R", 1)) {
    AxisId axis = AxisId::kAz;
    Direction dir = Direction::kNone;
    const char* name = "";
    if (text::iequals(arg, "cw")) dir = Direction::kCw, name = "CW";
    if (text::iequals(arg, "ccw")) dir = Direction::kCcw, name = "CCW";
    if (text::iequals(arg, "up")) axis = AxisId::kEl, dir = Direction::kCw, name = "UP";
    if (text::iequals(arg, "down")) axis = AxisId::kEl, dir = Direction::kCcw, name = "DOWN";
    if (dir == Direction::kNone) return error(out, "SYNTAX");
    if (!enabled_) return error(out, "DISABLED");
    const Error e = controller_.move(axis, dir);
    if (e != Error::kOk) return error(out, error_reason(e));
    return send(out, "$OK,R,%s", name);
  }
  if (is("Q", 0)) return write_state(out);
  error(out, known() ? "SYNTAX" : "UNKNOWN");
}

void SeedSession::write_state(ByteSink& out) {
  const RotatorStatus s = controller_.status();
  const char* fault = "NONE";
  if (s.az.fault != AxisFault::kNone) fault = axis_fault_name(s.az.fault);
  if (s.el.present && s.el.fault != AxisFault::kNone) fault = axis_fault_name(s.el.fault);
  send(out, "$Q,%.1f,%.1f,%d,%s,%s,%s,%s", az_reading(s, 1),
       s.el.present ? one_decimal(s.el.position_deg) : 0.0, s.speed_pct, enabled_ ? "E" : "D",
       direction_name(s.az, false), direction_name(s.el, true), fault);
}

}  // namespace rotord::protocol
