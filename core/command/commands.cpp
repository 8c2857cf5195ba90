#include "command/commands.hpp"

#include <cmath>
#include <cstring>

#include "command/json_args.hpp"
#include "command/typed.hpp"
#include "net/line_access.hpp"

namespace rotord::command {
namespace {

using web::JsonType;

bool is_whole(double v) {
  return std::floor(v) == v;
}

Result ok(Reply reply = Reply::kOk) {
  Result r;
  r.reply = reply;
  return r;
}

}  // namespace

std::span<const Def> Commands::table() {
  return kCommandTable;
}

const Def& Commands::def(Id id) {
  return kCommandTable[static_cast<std::size_t>(id)];
}

const Def* Commands::find(std::string_view name) {
  for (const Def& d : kCommandTable)
    if (d.name == name) return &d;
  return nullptr;
}

Result Commands::locked_refusal() const {
  const access::ControlLock& lock = controller_.control_lock();
  const Millis left = lock.until() > transport_now_ ? lock.until() - transport_now_ : 0;
  return refusedf(Status::kLocked,
                  "another operator holds the control lock (%s, %lld s left); STOP still works",
                  lock.holder().kind == access::LockHolder::Kind::kToken ? lock.holder().label
                                                                         : "a web session",
                  static_cast<long long>((left + 999) / 1000));
}

void Commands::told(const Def& command, const Request& r, const Result& result) {
  const bool at = result.ok() && result.reply == Reply::kGoto;
  command::told(controller_, {r.front, r.peer}, command.name, status_word(result.status),
                at && result.has_az_target ? result.az_target_deg : NAN,
                at && result.has_el_target ? result.el_target_deg : NAN);
}

Result Commands::execute(Id id, const Request& r) {
  const Def& d = def(id);
  Result result = (this->*d.run)(r);
  told(d, r, result);
  return result;
}

Result Commands::admit(const Gate& gate, const Authority& who, const Def* command,
                       const Request* r) {
  Result a = admit_only(gate, who);
  if (!a.ok() && command != nullptr && r != nullptr) told(*command, *r, a);
  return a;
}

Result Commands::admit_only(const Gate& gate, const Authority& who) const {
  if (static_cast<int>(who.granted) < static_cast<int>(gate.need))
    return refused(Status::kForbidden, "not allowed for this caller");
  // Failed closed (the access settings could not be read at start-up):
  // STOP, login and logout, and reading only, from anyone, until fixed.
  if (controller_.settings().access_unreadable() && gate.changes && gate.need != Need::kPublic)
    return refused(Status::kUnavailable,
                   "the access settings in the stored settings cannot be read: only STOP and "
                   "status until they are fixed (docs/security.md)");
  if (gate.locked && controller_.control_lock().held() && !who.holds_lock) return locked_refusal();
  return {};
}

Result Commands::run(Id id, const Request& r) {
  Result a = admit(def(id).gate, r.who, &def(id), &r);
  if (!a.ok()) return a;
  return execute(id, r);
}

Result Commands::from_broker(Id id, const access::Peer& broker, std::string_view body) {
  const Request r{{Need::kControl, false}, broker, body, "mqtt"};
  const char* why = nullptr;
  if (def(id).gate.need == Need::kPublic) {
    // STOP: for anyone.
  } else if (!controller_.settings().b(settings::Id::kMqttControl)) {
    why = "mqtt.control is off: only stop is obeyed from the broker";
  } else if (!access::may_control(controller_.settings(), broker)) {
    // The line protocols' allow-list, applied to the broker's address (the
    // REST API's answer to a read-only caller is a 403 too).
    why = "read-only: the broker's address is not in access.control_networks";
  }
  if (why == nullptr) return run(id, r);
  const Result no = refused(Status::kForbidden, why);
  told(def(id), r, no);
  return no;
}

void Commands::poll(Millis transport_now) {
  transport_now_ = transport_now;
  for (std::size_t n = 0; n < dead_man_.size(); ++n) {
    DeadMan& d = dead_man_[n];
    if (!d.armed || transport_now < d.until) continue;
    d.armed = false;
    const auto axis = static_cast<AxisId>(n);
    const RotatorStatus s = controller_.status();
    const AxisStatus& a = axis == AxisId::kAz ? s.az : s.el;
    // Only the jog the hold started: a go-to given since stays.
    if (a.jogging) controller_.move(axis, Direction::kNone);
  }
}

void Commands::arm_dead_man(AxisId axis, Millis hold_ms) {
  DeadMan& d = dead_man_[static_cast<std::size_t>(axis)];
  d.armed = hold_ms > 0;
  d.until = transport_now_ + hold_ms;
}

void Commands::stop_all() {
  dead_man_ = {};
  command::stop(controller_, {});
}

Result Commands::stop(const Request&) {
  stop_all();
  return ok();
}

Result Commands::go_to(const Request& r) {
  Member m[] = {
      {"az", JsonType::kNumber}, {"el", JsonType::kNumber}, {"unwrapped", JsonType::kBool}};
  Result done = ok(Reply::kGoto);
  if (!read_members(r.body, m, done)) return done;
  if (!m[0].present && !m[1].present)
    return refused(Status::kBadRequest, "give az and/or el (degrees)");
  const AzTarget mode =
      m[2].present && m[2].value.boolean ? AzTarget::kUnwrapped : AzTarget::kCompass;
  const Limits l = controller_.limits();
  if (m[0].present && !controller_.resolve_az(static_cast<float>(m[0].value.number), mode))
    return refusedf(Status::kUnprocessable, "az %g is outside the travel %g..%g", m[0].value.number,
                    static_cast<double>(l.az_min_deg), static_cast<double>(l.az_max_deg));
  if (m[1].present && l.has_el &&
      (m[1].value.number < l.el_min_deg || m[1].value.number > l.el_max_deg))
    return refusedf(Status::kUnprocessable, "el %g is outside the travel %g..%g", m[1].value.number,
                    static_cast<double>(l.el_min_deg), static_cast<double>(l.el_max_deg));
  std::optional<float> az;
  std::optional<float> el;
  if (m[0].present) az = static_cast<float>(m[0].value.number);
  if (m[1].present) el = static_cast<float>(m[1].value.number);
  // Each caller's address is its own stream for the continuity rule (MQTT
  // arrives here as the broker).
  const CommandSource source = (CommandSource{1} << 62) |
                               (static_cast<CommandSource>(r.peer.kind) << 32) |
                               r.peer.address_hash();
  if (const Error e = command::go_to(controller_, {}, az, el, mode, source); e != Error::kOk)
    return refused_by(e);
  const RotatorStatus s = controller_.status();
  done.has_az_target = az.has_value();
  done.has_el_target = el.has_value();
  done.az_target_deg = s.az.target_deg;
  done.el_target_deg = s.el.target_deg;
  return done;
}

namespace {

/// The direction and axis a move names ("up"/"down" are the elevation's).
Result read_direction(const Member& dir_member, const Member& axis_member, Direction& dir,
                      std::optional<AxisId>& axis) {
  const std::string_view dir_text = dir_member.value.text;
  if (dir_text == "cw" || dir_text == "ccw") {
    dir = dir_text == "cw" ? Direction::kCw : Direction::kCcw;
  } else if (dir_text == "up" || dir_text == "down") {
    dir = dir_text == "up" ? Direction::kCw : Direction::kCcw;
    axis = AxisId::kEl;
  } else if (dir_text != "stop") {
    return refused(Status::kUnprocessable, "dir must be cw, ccw, up, down or stop");
  }
  if (!axis_member.present) return {};
  const std::string_view a = axis_member.value.text;
  if (a != "az" && a != "el") return refused(Status::kUnprocessable, "axis must be az or el");
  const AxisId named = a == "az" ? AxisId::kAz : AxisId::kEl;
  if (axis && *axis != named)
    return refused(Status::kUnprocessable, "up and down move the elevation axis");
  axis = named;
  return {};
}

}  // namespace

Result Commands::move(const Request& r) {
  Member m[] = {{"axis", JsonType::kString},
                {"dir", JsonType::kString},
                {"speed", JsonType::kNumber},
                {"hold_ms", JsonType::kNumber}};
  if (Result bad; !read_members(r.body, m, bad)) return bad;
  if (!m[1].present) return refused(Status::kBadRequest, "give dir: cw, ccw, up, down or stop");
  Direction dir = Direction::kNone;
  std::optional<AxisId> axis;
  if (Result bad = read_direction(m[1], m[0], dir, axis); !bad.ok()) return bad;
  int speed = -1;
  if (m[2].present) {
    const double v = m[2].value.number;
    if (!is_whole(v) || v < 1 || v > 100)
      return refused(Status::kUnprocessable, "speed must be a whole number 1..100 (%)");
    speed = static_cast<int>(v);
  }
  Millis hold = kDefaultHoldMs;
  if (m[3].present) {
    const double v = m[3].value.number;
    if (!is_whole(v) ||
        (v != 0 && (v < static_cast<double>(kMinHoldMs) || v > static_cast<double>(kMaxHoldMs))))
      return refused(Status::kUnprocessable, "hold_ms must be 0 (no dead-man) or 100..10000");
    hold = static_cast<Millis>(v);
  }
  if (dir == Direction::kNone && !axis) return stop(r);
  const AxisId moved = axis.value_or(AxisId::kAz);
  if (const Error e = command::move(controller_, {}, moved, dir, speed); e != Error::kOk)
    return refused_by(e);
  arm_dead_man(moved, dir == Direction::kNone ? 0 : hold);
  return ok();
}

Result Commands::park(const Request&) {
  if (const Error e = command::park(controller_, {}); e != Error::kOk) return refused_by(e);
  return ok();
}

Result Commands::reset(const Request&) {
  if (command::reset(controller_, {}) != Error::kOk)
    return refused(Status::kConflict, "the emergency stop is active: release it, then reset");
  return ok();
}

Result Commands::speed(const Request& r) {
  Member m[] = {{"speed_pct", JsonType::kNumber}};
  if (Result bad; !read_members(r.body, m, bad)) return bad;
  if (!m[0].present) return refused(Status::kBadRequest, "give speed_pct");
  if (!is_whole(m[0].value.number) ||
      command::set_speed(controller_, {}, static_cast<int>(m[0].value.number)) != Error::kOk)
    return refused(Status::kUnprocessable, "speed_pct must be a whole number 1..100");
  return ok();
}

Result Commands::place(const Request& r) {
  Result done = ok(Reply::kPlace);
  if (Result bad = read_place(r.body, done.place); !bad.ok()) return bad;
  PlaceAim aim;
  const Error e = turn_to_place(controller_, {}, done.place, aim);
  if (!aim.reachable) return refused(Status::kUnprocessable, aim.why);
  if (e != Error::kOk) return refused_by(e);
  done.bearing = aim.bearing;
  return done;
}

Result Commands::preset(const Request& r) {
  PresetBody b;
  if (const char* why = read_preset_body(r.body, b, true)) return refused(Status::kBadRequest, why);
  settings::Preset p;
  if (const Error e = turn_to_preset(controller_, {}, b.name, p); e == Error::kNotFound) {
    return refused(Status::kNotFound, "no preset of that name");
  } else if (e != Error::kOk) {
    const Limits l = controller_.limits();
    return refusedf(e == Error::kFaulted ? Status::kConflict : Status::kUnprocessable,
                    "%s: heading %.1f, travel %g..%g", error_name(e), p.az_deg,
                    static_cast<double>(l.az_min_deg), static_cast<double>(l.az_max_deg));
  }
  Result done = ok(Reply::kPreset);
  done.preset_az_deg = p.az_deg;
  std::memcpy(done.preset_name, p.name, sizeof done.preset_name);
  return done;
}

}  // namespace rotord::command
