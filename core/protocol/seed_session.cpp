#include "protocol/seed_session.hpp"

#include <array>
#include <cmath>
#include <cstdio>

#include "command/typed.hpp"
#include "protocol/alarm_word.hpp"
#include "protocol/reading_format.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

/// One reply line, CR LF ended, in one write.
template <typename... Args>
void send(ByteSink& out, const char* fmt, Args... args) {
  SeedSession::Reply(SeedSession::kReplyRules).line(out, fmt, args...);
}

void error(ByteSink& out, const char* reason) {
  send(out, "$ERR,%s", reason);
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

const SeedSession::Command SeedSession::kCommands[] = {
    {"E", 0, &SeedSession::enable, "$E: enable the drive for this session", false},
    {"D", 0, &SeedSession::disable, "$D: stop every motion and disable", false},
    {"S", 1, &SeedSession::speed, "$S,n: speed 1..100 %", true},
    {"R", 1, &SeedSession::run, "$R,cw|ccw|up|down: run until $D, a limit or a fault", true},
    {"Q", 0, &SeedSession::query, "$Q: position, speed, enable, directions, fault", false},
};

std::span<const SeedSession::Command> SeedSession::commands() {
  return kCommands;
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
  bool known = false;
  for (const Command& c : kCommands) {
    if (!text::iequals(fields[0], c.name)) continue;
    known = true;
    if (count != c.args + 1u) continue;
    if (!command_arrives(c.run == &SeedSession::disable)) return;
    if (c.changes_state && !may_control(controller_, c.name)) return error(out, "DENIED");
    return (this->*c.run)(fields[1], out);
  }
  error(out, known ? "SYNTAX" : "UNKNOWN");
}

void SeedSession::enable(std::string_view, ByteSink& out) {
  enabled_ = true;
  send(out, "$OK,E");
}

void SeedSession::disable(std::string_view, ByteSink& out) {
  // Disable is also the stop: every motion ends, whoever started it.
  command::stop(controller_, origin());
  enabled_ = false;
  send(out, "$OK,D");
}

void SeedSession::speed(std::string_view arg, ByteSink& out) {
  long pct = 0;
  if (!text::parse_int(arg, pct)) return error(out, "SYNTAX");
  if (pct < 1 || pct > 100) return error(out, "RANGE");
  command::set_speed(controller_, origin(), static_cast<int>(pct));
  send(out, "$OK,S,%ld", pct);
}

void SeedSession::run(std::string_view arg, ByteSink& out) {
  AxisId axis = AxisId::kAz;
  Direction dir = Direction::kNone;
  const char* name = "";
  if (text::iequals(arg, "cw")) dir = Direction::kCw, name = "CW";
  if (text::iequals(arg, "ccw")) dir = Direction::kCcw, name = "CCW";
  if (text::iequals(arg, "up")) axis = AxisId::kEl, dir = Direction::kCw, name = "UP";
  if (text::iequals(arg, "down")) axis = AxisId::kEl, dir = Direction::kCcw, name = "DOWN";
  if (dir == Direction::kNone) return error(out, "SYNTAX");
  if (!enabled_) return error(out, "DISABLED");
  const Error e = command::move(controller_, origin(), axis, dir);
  if (e != Error::kOk) return error(out, alarm_word(e));
  send(out, "$OK,R,%s", name);
}

void SeedSession::query(std::string_view, ByteSink& out) {
  write_state(out);
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
