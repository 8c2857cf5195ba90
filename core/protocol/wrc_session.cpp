#include "protocol/wrc_session.hpp"

#include <cstdio>

#include "protocol/reading_format.hpp"
#include "rotator/controller.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

/// Formats one reply line into a fixed buffer and writes it with CR LF.
class Reply {
 public:
  // A fixed line goes out as it is (and a '%' in it stays a '%').
  void send(ByteSink& out, const char* line) { send(out, "%s", line); }

  template <typename... Args>
  void send(ByteSink& out, const char* fmt, Args... args) {
    int n = std::snprintf(buf_, sizeof(buf_) - 2, fmt, args...);
    if (n < 0) return;
    std::size_t len = static_cast<std::size_t>(n) < sizeof(buf_) - 2 ? static_cast<std::size_t>(n)
                                                                     : sizeof(buf_) - 3;
    buf_[len++] = '\r';
    buf_[len++] = '\n';
    out.write(std::string_view(buf_, len));
  }

 private:
  char buf_[192];
};

const char* error_reason(Error e) {
  switch (e) {
    case Error::kFaulted:
      return "FAULT";
    case Error::kLimit:
      return "LIMIT";
    case Error::kNotSupported:
      return "NOT SUPPORTED";
    default:
      return "INVALID ARGUMENT";
  }
}

bool parse_float(std::string_view s, float& out) {
  double d = 0;
  if (!text::parse_double(text::trim(s), d)) return false;
  out = static_cast<float>(d);
  return true;
}

}  // namespace

void WrcSession::receive(std::string_view bytes, ByteSink& out) {
  lines_.feed(bytes, [&](std::string_view line, bool overflowed) {
    if (overflowed) {
      Reply().send(out, "ERROR COMMAND TOO LONG");
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
  const RotatorStatus s = controller_.status();
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
  Reply reply;
  if (s.el.present) {
    reply.send(out, "%s AZ=%.1f EL=%.1f SPEED=%d FLAGS=%s", prefix, az_reading(s, 1),
               one_decimal(s.el.position_deg), s.speed_pct, flags);
  } else {
    reply.send(out, "%s AZ=%.1f SPEED=%d FLAGS=%s", prefix, az_reading(s, 1), s.speed_pct, flags);
  }
}

void WrcSession::handle_line(std::string_view line, ByteSink& out) {
  line = text::trim(line);
  if (line.empty()) return;
  std::string_view rest = line;
  const std::string_view name = text::next_token(rest);
  const std::string_view arg = text::trim(rest);
  const bool has_arg = !arg.empty();
  Reply reply;
  auto is = [&](const char* word) { return text::iequals(name, word); };

  // The commands that move the rotator or change a setting; a read-only
  // client (access.control_networks) gets an error for them. STOP is not
  // among them.
  if (has_arg && !may_control(controller_)) {
    for (const char* word : {"AZ", "EL", "MOVE", "SPEED", "AZOFFSET"})
      if (is(word)) return reply.send(out, "ERROR NOT ALLOWED");
  }
  if ((is("PARK") || is("RESET")) && !may_control(controller_))
    return reply.send(out, "ERROR NOT ALLOWED");

  if (is("AZ") && has_arg) {
    float az = 0;
    if (!parse_float(arg, az)) return reply.send(out, "ERROR INVALID AZIMUTH");
    const Error e = controller_.go_to(az, std::nullopt);
    if (e == Error::kOutOfRange || e == Error::kInvalidArgument)
      return reply.send(out, "ERROR INVALID AZIMUTH");
    if (e != Error::kOk) return reply.send(out, "ERROR %s", error_reason(e));
    return reply.send(out, "OK AZ %.2f", static_cast<double>(az));
  }
  if (is("AZ?") && !has_arg) {
    return reply.send(out, "OK AZ %.1f", az_reading(controller_.status(), 1));
  }
  if (is("EL") && has_arg) {
    float el = 0;
    if (!controller_.has_el()) return reply.send(out, "ERROR NOT SUPPORTED");
    if (!parse_float(arg, el)) return reply.send(out, "ERROR INVALID ELEVATION");
    const Error e = controller_.go_to(std::nullopt, el);
    if (e == Error::kOutOfRange || e == Error::kInvalidArgument)
      return reply.send(out, "ERROR INVALID ELEVATION");
    if (e != Error::kOk) return reply.send(out, "ERROR %s", error_reason(e));
    return reply.send(out, "OK EL %.2f", static_cast<double>(el));
  }
  if (is("EL?") && !has_arg) {
    if (!controller_.has_el()) return reply.send(out, "ERROR NOT SUPPORTED");
    return reply.send(out, "OK EL %.1f", one_decimal(controller_.status().el.position_deg));
  }
  if (is("MOVE") && has_arg) {
    AxisId axis = AxisId::kAz;
    Direction dir = Direction::kNone;
    if (text::iequals(arg, "CW")) dir = Direction::kCw;
    if (text::iequals(arg, "CCW")) dir = Direction::kCcw;
    if (text::iequals(arg, "UP")) axis = AxisId::kEl, dir = Direction::kCw;
    if (text::iequals(arg, "DOWN")) axis = AxisId::kEl, dir = Direction::kCcw;
    if (dir == Direction::kNone) return reply.send(out, "ERROR INVALID DIRECTION");
    const Error e = controller_.move(axis, dir);
    if (e != Error::kOk) return reply.send(out, "ERROR %s", error_reason(e));
    char upper[8] = {};
    for (std::size_t i = 0; i < arg.size() && i < sizeof(upper) - 1; ++i)
      upper[i] = (arg[i] >= 'a' && arg[i] <= 'z') ? static_cast<char>(arg[i] - 32) : arg[i];
    return reply.send(out, "OK MOVE %s", upper);
  }
  if (is("STATE") && !has_arg) return write_state(out, "OK STATE");
  if (is("FAULT?") && !has_arg) {
    const RotatorStatus s = controller_.status();
    if (s.el.present)
      return reply.send(out, "OK FAULT AZ=%s EL=%s", axis_fault_name(s.az.fault),
                        axis_fault_name(s.el.fault));
    return reply.send(out, "OK FAULT AZ=%s", axis_fault_name(s.az.fault));
  }
  if (is("SPEED") && has_arg) {
    long speed = 0;
    if (!text::parse_int(arg, speed) || speed < 1 || speed > 100)
      return reply.send(out, "ERROR INVALID SPEED");
    controller_.set_speed_pct(static_cast<int>(speed));
    // The WRC firmware prints the speed as an Arduino double: two decimals.
    return reply.send(out, "OK SPEED %.2f", static_cast<double>(speed));
  }
  if (is("SPEED?") && !has_arg)
    return reply.send(out, "OK SPEED %d", controller_.status().speed_pct);
  if (is("STOP") && !has_arg) {
    controller_.stop();
    return reply.send(out, "OK STOP");
  }
  if (is("PARK") && !has_arg) {
    const Error e = controller_.park();
    if (e != Error::kOk) return reply.send(out, "ERROR %s", error_reason(e));
    return reply.send(out, "OK PARK");
  }
  if (is("RESET") && !has_arg) {
    if (controller_.reset() != Error::kOk) return reply.send(out, "ERROR ESTOP");
    return reply.send(out, "OK RESET");
  }
  if (is("MONITOR") && has_arg) {
    long on = 0;
    if (!text::parse_int(arg, on) || (on != 0 && on != 1))
      return reply.send(out, "ERROR INVALID ARGUMENT");
    monitor_ = on == 1;
    last_push_ = now_;
    return reply.send(out, "OK MONITOR %d", monitor_ ? 1 : 0);
  }
  if (is("INFO") && !has_arg) return reply.send(out, "OK INFO rotord %s", version_);
  if (is("AZLIMITS?") && !has_arg) {
    const Limits l = controller_.limits();
    return reply.send(out, "OK AZLIMITS MIN=%g MAX=%g", static_cast<double>(l.az_min_deg),
                      static_cast<double>(l.az_max_deg));
  }
  if (is("AZOFFSET") && has_arg) {
    float offset = 0;
    if (!parse_float(arg, offset)) return reply.send(out, "ERROR INVALID AZIMUTH OFFSET");
    if (controller_.settings().set(Id::kAzOffsetDeg, offset).error != Error::kOk)
      return reply.send(out, "ERROR INVALID AZIMUTH OFFSET");
    return reply.send(out, "OK AZOFFSET %.2f", static_cast<double>(offset));
  }
  if (is("AZOFFSET?") && !has_arg) {
    return reply.send(out, "OK AZOFFSET %.2f", controller_.settings().get(Id::kAzOffsetDeg));
  }
  reply.send(out, "ERROR INVALID COMMAND");
}

}  // namespace rotord::protocol
