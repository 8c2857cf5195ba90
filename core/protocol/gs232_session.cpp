#include "protocol/gs232_session.hpp"

#include <cstdio>

#include "protocol/gs232_calibration.hpp"
#include "protocol/gs232_help.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

constexpr int kMaxStepS = 999;
constexpr int kMaxElDeg = 180;

char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

/// One angle or interval field: one to three decimal digits. The manual asks
/// for exactly three (zero-padded); fewer are accepted because nothing is
/// ambiguous about them. Signs, decimals and longer numbers are errors.
bool parse_field(std::string_view s, int& value) {
  if (s.empty() || s.size() > 3) return false;
  int v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  value = v;
  return true;
}

/// Formats a data reply (which always ends in CR LF) and sends it in one write.
/// A reply that cannot fit goes out as the protocol's error, never as silence
/// (issue 11).
template <typename... Args>
void send(ByteSink& out, const char* fmt, Args... args) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof(buf), fmt, args...);
  if (n <= 0 || static_cast<std::size_t>(n) >= sizeof(buf)) return out.write(Gs232Session::kError);
  out.write(std::string_view(buf, static_cast<std::size_t>(n)));
}

}  // namespace

void Gs232Session::done(ByteSink& out) {
  // The real controllers send a CR after every command. Hamlib's GS-232A/B
  // backends never read it (they flush the input before the next command, 50
  // ms later); the generic ones (602, 607, 608) write the next command at once
  // and can take it for the position reply, hence gs232.ack_writes.
  if (controller_.settings().b(Id::kGs232AckWrites)) out.write("\r");
}

void Gs232Session::reply(Error e, ByteSink& out) {
  if (e != Error::kOk) return out.write(kError);
  done(out);
}

bool Gs232Session::is_b() const {
  return controller_.settings().i(Id::kGs232Variant) == 1;
}

gs232::AzRange Gs232Session::range() const {
  return gs232::az_range(controller_.settings(), controller_.limits());
}

void Gs232Session::receive(std::string_view bytes, ByteSink& out) {
  lines_.feed(bytes, [&](std::string_view line, bool overflowed) {
    if (overflowed) {
      // Too long even for a full timed list: like any bad M / W, the stored
      // list is gone and nothing moves.
      pending_ = Pending::kNone;
      list_size_ = 0;
      stop_list();
      out.write(kError);
      return;
    }
    handle_line(line, out);
  });
}

void Gs232Session::poll(Millis /*now*/, ByteSink& /*out*/) {
  // The controller's clock, not the transport's: the list runs in the same
  // (possibly simulated) time as the motion it commands.
  if (!running_ || controller_.now() < next_step_at_) return;
  if (list_index_ + 1u >= list_size_) {
    running_ = false;  // the last point was reached; N keeps reporting it
    return;
  }
  ++list_index_;
  next_step_at_ += step_ms_;
  if (go_to_point(list_index_) != Error::kOk) running_ = false;
}

void Gs232Session::handle_line(std::string_view line, ByteSink& out) {
  line = text::trim(line);
  if (pending_ != Pending::kNone) {
    if (line.empty()) return;  // the Enter after "are you sure?" is not an answer yet
    return confirm(line, out);
  }
  // Hamlib's GS-232B backend sends an extra CR after every command without a
  // reply; empty commands are ignored so that nothing answers it.
  if (line.empty()) return;
  const char cmd = upper(line[0]);
  const std::string_view rest = text::slice(line, 1);
  // Turning, speed, timed lists, calibration and P36/P45: refused with the
  // controller's error to a read-only client (access.control_networks).
  // S, A and E (stop) are not among them.
  if (std::string_view("MWRLUDXTOFP").find(cmd) != std::string_view::npos &&
      !may_control(controller_))
    return out.write(kError);
  if (cmd == 'M' || cmd == 'W') return position_command(cmd == 'W', rest, out);

  // Every other command is a letter and at most three characters; spaces
  // inside are ignored ("C 2" as the manual's help screen prints it).
  char arg_buf[4];
  std::size_t n = 0;
  for (char c : rest) {
    if (c == ' ' || c == '\t') continue;
    if (n == 3) return out.write(kError);
    arg_buf[n++] = upper(c);
  }
  const std::string_view arg(arg_buf, n);
  const bool bare = arg.empty();
  const bool b = is_b();

  switch (cmd) {
    case 'C':
      if (bare || arg == "2") return report(bare ? 'C' : '2', out);
      break;
    case 'B':
      if (bare) return report('B', out);
      break;
    case 'R':
    case 'L':
    case 'U':
    case 'D':
      if (bare) {
        stop_list();
        const AxisId axis = cmd == 'R' || cmd == 'L' ? AxisId::kAz : AxisId::kEl;
        const Direction dir = cmd == 'R' || cmd == 'U' ? Direction::kCw : Direction::kCcw;
        return reply(controller_.move(axis, dir), out);
      }
      break;
    case 'A':
    case 'E':
      if (bare) {
        stop_list();
        const AxisId axis = cmd == 'A' ? AxisId::kAz : AxisId::kEl;
        if (axis == AxisId::kEl && !controller_.has_el()) return out.write(kError);
        controller_.move(axis, Direction::kNone);  // a faulted axis is stopped anyway
        return done(out);
      }
      break;
    case 'S':
      if (bare) {
        // Cancels the running command and the timed list's stepping; the list
        // stays stored for another T, as on the real controller.
        stop_list();
        controller_.stop();
        return done(out);
      }
      break;
    case 'X':
      if (arg.size() == 1 && arg[0] >= '1' && arg[0] <= '4') {
        // Four steps over the speed range: X1 and X2 are the slow half of a
        // two-speed drive, X3 and X4 the fast half. Takes effect while turning.
        controller_.set_speed_pct((arg[0] - '0') * 25);
        return done(out);
      }
      break;
    case 'T':
      if (bare && list_size_ > 0) {
        // Point 1 again now (the long-form M / W already turned there), then
        // one point every sss seconds: point k is due k-1 intervals after T.
        list_index_ = 0;
        next_step_at_ = controller_.now() + step_ms_;
        running_ = go_to_point(0) == Error::kOk;
        return running_ ? done(out) : out.write(kError);
      }
      break;
    case 'N':
      if (bare && list_size_ > 0)
        return send(out, "+%04u+%04u\r\n", static_cast<unsigned>(list_index_ + 1u),
                    static_cast<unsigned>(list_size_));
      break;
    case 'O':
    case 'F':
      if (bare || arg == "2") return calibration(bare ? AxisId::kAz : AxisId::kEl, cmd == 'F', out);
      break;
    case 'H':
      if (bare) return help(1, out);
      if (arg == "2") return help(2, out);
      if (arg == "3" && b) return help(3, out);
      break;
    case 'P':
      if (b && (arg == "36" || arg == "45")) {
        // The GS-232B keeps the mode over power cycles; here it is a setting,
        // which the port's SettingsSaver writes like every protocol change.
        controller_.settings().set(Id::kGs232AzRange, arg == "36" ? 1 : 2);
        return done(out);
      }
      break;
    case 'Z':
      if (b && bare) {
        // Ignored in 450 mode, as on the GS-232B.
        if (range() == gs232::AzRange::k360) south_centre_ = !south_centre_;
        return done(out);
      }
      break;
    default:
      break;
  }
  out.write(kError);
}

void Gs232Session::position_command(bool with_el, std::string_view args, ByteSink& out) {
  // Any M or W replaces the stored list: even a bare one, which the manual
  // answers with the error prompt after clearing the memories.
  stop_list();
  list_size_ = 0;
  list_index_ = 0;
  const int full_scale = gs232::full_scale_deg(range());
  int fields[3] = {0, 0, 0};
  std::size_t count = 0;
  bool ok = true;
  std::string_view rest = args;
  for (std::string_view token = text::next_token(rest); !token.empty();
       token = text::next_token(rest), ++count) {
    int value = 0;
    if (!parse_field(token, value)) {
      ok = false;
      break;
    }
    if (count < 3) fields[count] = value;
    if (count == 0) continue;  // the interval of a list or the first angle; checked below
    // Fields after the interval: angles, azimuth first, then elevation for W.
    const std::size_t index = (count - 1) / (with_el ? 2 : 1);
    const bool is_el = with_el && (count - 1) % 2 == 1;
    if (index >= kMaxListPoints || value > (is_el ? kMaxElDeg : full_scale)) {
      ok = false;
      break;
    }
    if (is_el) {
      list_[index].el_deg = static_cast<std::int16_t>(value);
    } else {
      list_[index] = {static_cast<std::int16_t>(value), -1};
    }
  }
  if (!ok || count == 0) return out.write(kError);

  // Short forms: Maaa, Waaa eee.
  if ((!with_el && count == 1) || (with_el && count == 2)) {
    if (fields[0] > full_scale || (with_el && fields[1] > kMaxElDeg)) return out.write(kError);
    const Error e = go(fields[0], with_el ? std::optional<int>(fields[1]) : std::nullopt);
    return reply(e, out);
  }
  // Long forms: Msss aaa aaa ... (at least two angles), Wsss aaa eee ... (pairs).
  const std::size_t points = with_el ? (count - 1) / 2 : count - 1;
  const bool shape_ok = with_el ? (count - 1) % 2 == 0 && points >= 1 : points >= 2;
  if (!shape_ok || fields[0] < 1 || fields[0] > kMaxStepS) return out.write(kError);
  list_size_ = static_cast<std::uint16_t>(points);
  step_ms_ = static_cast<Millis>(fields[0]) * 1000;
  if (go_to_point(0) != Error::kOk) {
    list_size_ = 0;
    return out.write(kError);
  }
  done(out);
}

Error Gs232Session::go(int az_deg, std::optional<int> el_deg) {
  const gs232::AzGoal goal = gs232::az_goal(az_deg, controller_.limits());
  // An azimuth-only rotator ignores the elevation field: Hamlib's 611 model
  // always sends one (W010 000).
  std::optional<float> el;
  if (el_deg && controller_.has_el()) el = static_cast<float>(*el_deg);
  // go_to checks both axes before it moves either: a target outside the
  // travel moves nothing.
  return controller_.go_to(goal.az_deg, el, goal.mode);
}

Error Gs232Session::go_to_point(std::size_t index) {
  const Point& p = list_[index];
  return go(p.az_deg, p.el_deg >= 0 ? std::optional<int>(p.el_deg) : std::nullopt);
}

void Gs232Session::report(char what, ByteSink& out) {
  const RotatorStatus s = controller_.status();
  const int az = gs232::report_az_deg(s.az.position_deg, range(), s.limits.az_continuous);
  // Without an elevation axis the elevation reads 0: C2 must still answer
  // (Hamlib's azimuth-only models 609 and 611 ask for it).
  const int el = s.el.present ? gs232::report_el_deg(s.el.position_deg) : 0;
  write_position(what, az, el, out);
}

void Gs232Session::write_position(char what, int az, int el, ByteSink& out) {
  if (is_b()) {
    if (what == 'C') return send(out, "AZ=%03d\r\n", az);
    if (what == 'B') return send(out, "EL=%03d\r\n", el);
    return send(out, "AZ=%03d  EL=%03d\r\n", az, el);
  }
  if (what == 'C') return send(out, "+0%03d\r\n", az);
  if (what == 'B') return send(out, "+0%03d\r\n", el);
  send(out, "+0%03d+0%03d\r\n", az, el);
}

void Gs232Session::calibration(AxisId axis, bool full_scale, ByteSink& out) {
  if (axis == AxisId::kEl && !controller_.has_el()) return out.write(kError);
  if (is_b() && !full_scale) {
    // The GS-232B asks before it overwrites the offset calibration.
    pending_ = axis == AxisId::kAz ? Pending::kAzOffset : Pending::kElOffset;
    return out.write("are you sure?\r\n");
  }
  const Error e = gs232::calibrate(
      controller_, axis, full_scale ? gs232::CalPoint::kFullScale : gs232::CalPoint::kOffset);
  if (e != Error::kOk) return out.write(kError);
  // The real controllers then show the reading the installer trims towards
  // ("+0450" / "AZ=450"; F2 both axes); after this calibration it is the stop
  // angle itself. The position the axis publishes catches up on the next tick.
  const settings::Settings& st = controller_.settings();
  const RotatorStatus s = controller_.status();
  int az = gs232::report_az_deg(s.az.position_deg, range(), s.limits.az_continuous);
  int el = s.el.present ? gs232::report_el_deg(s.el.position_deg) : 0;
  if (axis == AxisId::kAz) {
    az = gs232::report_az_deg(st.f(full_scale ? Id::kAzMaxDeg : Id::kAzMinDeg), range(), false);
  } else {
    el = gs232::report_el_deg(st.f(full_scale ? Id::kElMaxDeg : Id::kElMinDeg));
  }
  write_position(axis == AxisId::kAz ? 'C' : '2', az, el, out);
}

void Gs232Session::confirm(std::string_view answer, ByteSink& out) {
  const AxisId axis = pending_ == Pending::kAzOffset ? AxisId::kAz : AxisId::kEl;
  pending_ = Pending::kNone;
  if (answer.size() == 1 && upper(answer[0]) == 'N') return done(out);  // declined
  // Anything but Y or N is the next command, not an answer: a stop sent
  // instead of an answer must still stop.
  if (answer.size() != 1 || upper(answer[0]) != 'Y') return handle_line(answer, out);
  const Error e = gs232::calibrate(controller_, axis, gs232::CalPoint::kOffset);
  out.write(e == Error::kOk ? std::string_view("Completed\r\n") : kError);
}

void Gs232Session::help(int page, ByteSink& out) {
  out.write(gs232::help_page(page));
  if (page != 3) return;
  send(out, "---------- MODE ----------\r\nmode %d Degree\r\n%s Center\r\n",
       gs232::full_scale_deg(range()), south_centre_ ? "S" : "N");
}

}  // namespace rotord::protocol
