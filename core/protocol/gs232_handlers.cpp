// What each GS-232 command does on the controller, and its reply (the rows
// of Gs232Session::kCommands, gs232_session.cpp).
#include <array>
#include <cstdio>

#include "command/calibration.hpp"
#include "command/typed.hpp"
#include "protocol/gs232_detail.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using gs232::detail::parse_field;
using gs232::detail::send;
using gs232::detail::upper;
using settings::Id;

constexpr int kMaxStepS = 999;
constexpr int kMaxElDeg = 180;

}  // namespace

void Gs232Session::report_az(std::string_view, ByteSink& out) {
  report('C', out);
}

void Gs232Session::report_el(std::string_view, ByteSink& out) {
  report('B', out);
}

void Gs232Session::report_both(std::string_view, ByteSink& out) {
  report('2', out);
}

void Gs232Session::turn(AxisId axis, Direction dir, ByteSink& out) {
  stop_list();
  reply(command::move(controller_, origin(), axis, dir), out);
}

void Gs232Session::turn_cw(std::string_view, ByteSink& out) {
  turn(AxisId::kAz, Direction::kCw, out);
}

void Gs232Session::turn_ccw(std::string_view, ByteSink& out) {
  turn(AxisId::kAz, Direction::kCcw, out);
}

void Gs232Session::turn_up(std::string_view, ByteSink& out) {
  turn(AxisId::kEl, Direction::kCw, out);
}

void Gs232Session::turn_down(std::string_view, ByteSink& out) {
  turn(AxisId::kEl, Direction::kCcw, out);
}

void Gs232Session::stop_axis(AxisId axis, ByteSink& out) {
  stop_list();
  if (command::stop_axis(controller_, origin(), axis) != Error::kOk) return out.write(kError);
  done(out);
}

void Gs232Session::stop_az(std::string_view, ByteSink& out) {
  stop_axis(AxisId::kAz, out);
}

void Gs232Session::stop_el(std::string_view, ByteSink& out) {
  stop_axis(AxisId::kEl, out);
}

void Gs232Session::stop_all(std::string_view, ByteSink& out) {
  // Cancels the running command and the timed list's stepping; the list
  // stays stored for another T, as on the real controller.
  stop_list();
  command::stop(controller_, origin());
  done(out);
}

void Gs232Session::speed(std::string_view arg, ByteSink& out) {
  // Four steps over the speed range: X1 and X2 are the slow half of a
  // two-speed drive, X3 and X4 the fast half. Takes effect while turning.
  command::set_speed(controller_, origin(), (arg[0] - '0') * 25);
  done(out);
}

void Gs232Session::go_az(std::string_view fields, ByteSink& out) {
  position_command(false, fields, out);
}

void Gs232Session::go_az_el(std::string_view fields, ByteSink& out) {
  position_command(true, fields, out);
}

void Gs232Session::start_list(std::string_view, ByteSink& out) {
  if (list_size_ == 0) return out.write(kError);
  // Point 1 again now (the long-form M / W already turned there), then
  // one point every sss seconds: point k is due k-1 intervals after T.
  list_index_ = 0;
  next_step_at_ = controller_.now() + step_ms_;
  running_ = go_to_point(0) == Error::kOk;
  return running_ ? done(out) : out.write(kError);
}

void Gs232Session::list_point(std::string_view, ByteSink& out) {
  if (list_size_ == 0) return out.write(kError);
  send(out, "+%04u+%04u\r\n", static_cast<unsigned>(list_index_ + 1u),
       static_cast<unsigned>(list_size_));
}

void Gs232Session::offset_az(std::string_view, ByteSink& out) {
  calibration(AxisId::kAz, false, out);
}

void Gs232Session::offset_el(std::string_view, ByteSink& out) {
  calibration(AxisId::kEl, false, out);
}

void Gs232Session::full_scale_az(std::string_view, ByteSink& out) {
  calibration(AxisId::kAz, true, out);
}

void Gs232Session::full_scale_el(std::string_view, ByteSink& out) {
  calibration(AxisId::kEl, true, out);
}

void Gs232Session::help_1(std::string_view, ByteSink& out) {
  help(1, out);
}

void Gs232Session::help_2(std::string_view, ByteSink& out) {
  help(2, out);
}

void Gs232Session::help_3(std::string_view, ByteSink& out) {
  help(3, out);
}

void Gs232Session::scale_360(std::string_view, ByteSink& out) {
  // The GS-232B keeps the mode over power cycles; here it is a setting,
  // which the port's SettingsSaver writes like every protocol change.
  controller_.settings().set(Id::kGs232AzRange, 1);
  done(out);
}

void Gs232Session::scale_450(std::string_view, ByteSink& out) {
  controller_.settings().set(Id::kGs232AzRange, 2);
  done(out);
}

void Gs232Session::south_centre(std::string_view, ByteSink& out) {
  // Ignored in 450 mode, as on the GS-232B.
  if (range() == gs232::AzRange::k360) south_centre_ = !south_centre_;
  done(out);
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
  const Error e = command::go_to(controller_, origin(), goal.az_deg, el, goal.mode, source());
  if (e == Error::kOk)
    frame_.note_goto(goal.az_deg, controller_.az_continuity_shift_deg(),
                     controller_.last_goto_recognised(), el ? *el : 0.0f);
  return e;
}

Error Gs232Session::go_to_point(std::size_t index) {
  const Point& p = list_[index];
  return go(p.az_deg, p.el_deg >= 0 ? std::optional<int>(p.el_deg) : std::nullopt);
}

void Gs232Session::report(char what, ByteSink& out) {
  RotatorStatus s = controller_.status();
  // In this client's frame: a tracker's 002 that went to 362 reads 002.
  frame_.read(s.az.position_deg, s.el.position_deg, controller_.recognised_az_deg());
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
  const Error e = command::calibrate(controller_, origin(), axis,
                                     full_scale ? command::CalPoint::kHi : command::CalPoint::kLo);
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
  const Error e = command::calibrate(controller_, origin(), axis, command::CalPoint::kLo);
  out.write(e == Error::kOk ? std::string_view("Completed\r\n") : kError);
}

void Gs232Session::help(int page, ByteSink& out) {
  out.write(help_page(page));
  if (page != 3) return;
  send(out, "---------- MODE ----------\r\nmode %d Degree\r\n%s Center\r\n",
       gs232::full_scale_deg(range()), south_centre_ ? "S" : "N");
}

}  // namespace rotord::protocol
