#include "web/web_api.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "command/json_args.hpp"
#include "json/json_reader.hpp"
#include "util/slice.hpp"
#include "util/utc_time.hpp"
#include "web/care_api.hpp"
#include "web/place_api.hpp"
#include "web/recognition_report.hpp"

namespace rotord::web {
namespace {

using settings::Id;

const char* dir_name(Direction d) {
  return d == Direction::kCw ? "cw" : d == Direction::kCcw ? "ccw" : "none";
}

const char* lower_name(const char* upper, char* buf, std::size_t cap) {
  std::size_t n = 0;
  for (; upper[n] != '\0' && n + 1 < cap; ++n)
    buf[n] = (upper[n] >= 'A' && upper[n] <= 'Z') ? static_cast<char>(upper[n] + 32) : upper[n];
  buf[n] = '\0';
  return buf;
}

/// `sensor` is the *.sensor choice: 0 pot, 1 MA3, 2 magnetometer.
void write_axis(JsonWriter& w, const AxisStatus& a, int sensor) {
  static constexpr const char* kSensors[] = {"pot", "ma3", "mag"};
  static constexpr const char* kRawUnits[] = {"counts", "code", "deg"};
  const std::size_t s = sensor >= 0 && sensor <= 2 ? static_cast<std::size_t>(sensor) : 0;
  char name[24];
  w.begin_object()
      .member("position_deg", a.position_deg)
      .member("valid", a.position_valid)
      .member("speed_deg_s", a.speed_deg_s)
      .member("sensor", kSensors[s])
      .member("raw", a.raw)
      .member("raw_unit", kRawUnits[s]);
  // For the calibration page: the pot's wiper voltage and what raw spans.
  w.key("raw_volts");
  if (a.raw_full_scale > 0.0f && a.adc_ref_v > 0.0f) {
    w.number(static_cast<double>(a.raw) * a.adc_ref_v / a.raw_full_scale);
  } else {
    w.null();
  }
  w.key("raw_full_scale");
  if (a.raw_full_scale > 0.0f) {
    w.number(a.raw_full_scale);
  } else {
    w.null();
  }
  w.key("mag");
  if (a.mag_valid) {
    w.begin_object()
        .member("x", static_cast<int>(a.mag_x))
        .member("y", static_cast<int>(a.mag_y))
        .member("z", static_cast<int>(a.mag_z))
        .end_object();
  } else {
    w.null();
  }
  w.key("target_deg");
  if (a.has_target) {
    w.number(a.target_deg);
  } else {
    w.null();
  }
  w.member("jogging", a.jogging)
      .member("arrived", a.arrived)
      .member("state", lower_name(axis_state_name(a.state), name, sizeof(name)))
      .member("dir", dir_name(a.drive_dir))
      .member("fault", lower_name(axis_fault_name(a.fault), name, sizeof(name)))
      .member("limit_cw", a.limit_cw)
      .member("limit_ccw", a.limit_ccw)
      .member("switch_cw", a.switch_cw)
      .member("switch_ccw", a.switch_ccw)
      .member("coast_s", a.coast_s)
      .member("moves", a.moves)
      .member("readings_rejected", a.readings_rejected)
      .member("slips", a.slips)
      .member("slipping", a.slipping);
  w.key("outputs").begin_object();
  for (std::size_t n = 0; n < kOutputChannelCount; ++n)
    w.member(kOutputChannelNames[n], a.outputs.value[n]);
  w.end_object().end_object();
}

/// A command's result as the REST API's response.
void send_result(protocol::ByteSink& out, const ResponseOptions& options,
                 const command::Result& r) {
  send_json(out, command::http_status(r.status), options,
            [&](JsonWriter& w) { command::write_result(w, r); });
}

/// A command route's handler: the command layer runs it (the gate was
/// passed in Api::handle).
template <command::Id kId>
Api::Outcome run_command(Api& api, const Api::Call& call) {
  const command::Request request{api.authority(call.caller), call.peer, call.request.body};
  send_result(call.out, call.options, api.commands().execute(kId, request));
  return Api::Outcome::kDone;
}

/// A route row for a command of the command layer: its gate and help are
/// the command's. Only STOP takes a body of any type: it must always work.
template <command::Id kId>
constexpr Api::Route command_route(std::string_view path) {
  const command::Def& d = command::kCommandTable[static_cast<std::size_t>(kId)];
  return {path,  true, d.gate.need, d.gate.locked, kId != command::Id::kStop, run_command<kId>,
          d.help};
}

}  // namespace

Api::Api(const ApiContext& context)
    : ctx_(context),
      auth_(WebAuth::Config{context.crypto, context.pbkdf2_iterations, context.pbkdf2_slice,
                            context.log}),
      commands_(context.controller) {}

command::Authority Api::authority(const Caller& caller) const {
  const access::ControlLock& lock = ctx_.controller.control_lock();
  command::Authority who;
  if (WebAuth::enabled(ctx_.controller.settings())) {
    who.granted = caller.may_administer() ? Need::kAdmin
                  : caller.may_control()  ? Need::kControl
                  : caller.may_read()     ? Need::kRead
                                          : Need::kPublic;
  }
  who.holds_lock = lock.held() && caller.can_hold_lock() && lock.held_by(caller.holder);
  return who;
}

void Api::write_status(JsonWriter& w) const {
  const Controller& c = ctx_.controller;
  const RotatorStatus s = c.status();
  Controller& mutable_c = ctx_.controller;  // settings() is not const
  const settings::Settings& values = mutable_c.settings();
  w.begin_object()
      .member("version", ctx_.version)
      .member("time_ms", static_cast<long long>(c.now()));
  // Calendar time for the user (SNTP on the Pico W, the system clock on
  // Linux); null until known. The control tick never uses it.
  w.key("time_utc");
  char utc[32];
  const std::optional<std::int64_t> unix_ms =
      ctx_.wall_clock != nullptr ? ctx_.wall_clock->unix_ms() : std::nullopt;
  const std::size_t utc_len = unix_ms ? format_utc_iso8601(*unix_ms, utc, sizeof utc) : 0;
  if (utc_len > 0) {
    w.string(std::string_view(utc, utc_len));
  } else {
    w.null();
  }
  w.member("mode", mode_name(s.mode))
      .member("speed_pct", s.speed_pct)
      .member("speed_applies", ctx_.controller.speed_applies())
      .member("moving", s.moving())
      .member("fault", s.any_fault());
  w.key("limits")
      .begin_object()
      .member("az_min", s.limits.az_min_deg)
      .member("az_max", s.limits.az_max_deg)
      .member("az_continuous", s.limits.az_continuous)
      .member("has_el", s.limits.has_el)
      .member("el_min", s.limits.el_min_deg)
      .member("el_max", s.limits.el_max_deg)
      .end_object();
  w.key("park")
      .begin_object()
      .member("az", values.get(Id::kParkAzDeg))
      .member("el", values.get(Id::kParkElDeg))
      .end_object();
  w.key("lock");
  write_lock(w, nullptr);
  write_beam(w, s);
  write_recognition(w, c.recognition());
  write_odometer_status(w, ctx_.controller);
  // Only when something is wrong: a status every 100 ms stays short.
  const LoadReport* load = ctx_.load_report;
  if (values.access_unreadable() || (load != nullptr && !load->empty())) {
    w.key("settings_load").begin_object();
    w.member("access_unreadable", values.access_unreadable());
    w.key("dropped").begin_array();
    for (std::size_t n = 0; load != nullptr && n < load->size(); ++n)
      w.begin_object()
          .member("key", (*load)[n].key)
          .member("reason", (*load)[n].reason)
          .end_object();
    w.end_array();
    w.member("more", static_cast<long long>(load != nullptr ? load->more() : 0));
    w.end_object();
  }
  w.key("az");
  write_axis(w, s.az, values.i(Id::kAzSensor));
  w.key("el");
  if (s.el.present) {
    write_axis(w, s.el, values.i(Id::kElSensor));
  } else {
    w.null();
  }
  w.end_object();
}

void Api::poll(Millis transport_now) {
  transport_now_ = transport_now;
  auth_.flush_log(transport_now);
  access::ControlLock& lock = ctx_.controller.control_lock();
  if (lock.held() && transport_now >= lock.until()) {
    lock.release();
    auth_.log("rotord: control lock ran out");
  }
  auth_.sessions().expire(transport_now);
  work();
  work_passes(ctx_.passes_poll_budget);
  commands_.poll(transport_now);
}

// The route table: every endpoint of the REST API, once. Paths are exact;
// the same path may have a GET and a POST row.
using N = Api::Need;
using O = Api::Outcome;
const Api::Route Api::kRoutes[] = {
    {"/api/status", false, N::kRead, false, false, [](Api& a, const Call& c) { return a.get_status(c); },
     "position, state, faults, limits, the lock"},
    {"/api/events", false, N::kRead, false, false, [](Api& a, const Call& c) { return a.get_events(c); },
     "the status as Server-Sent Events"},
    {"/api/settings", false, N::kRead, false, false,
     [](Api& a, const Call& c) {
       a.get_settings(c.out, c.options);
       return O::kDone;
     },
     "every setting (secrets masked)"},
    {"/api/settings/schema", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.get_schema(c); },
     "the settings table: type, unit, range, default, help"},
    {"/api/auth", false, N::kRead, false, false,
     [](Api& a, const Call& c) {
       a.get_auth(c.caller, c.out, c.options);
       return O::kDone;
     },
     "who the caller is, and the lock"},
    {"/api/station", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.get_station(c); },
     "the rotords seen on the MQTT broker (docs/mqtt.md)"},
    {"/api/tokens", false, N::kAdmin, false, false,
     [](Api& a, const Call& c) {
       a.get_tokens(c.out, c.options);
       return O::kDone;
     },
     "the bearer tokens' names and scopes"},
    command_route<command::Id::kGoto>("/api/goto"),
    command_route<command::Id::kMove>("/api/move"),
    // STOP: always, for anyone, with any body.
    command_route<command::Id::kStop>("/api/stop"),
    command_route<command::Id::kPark>("/api/park"),
    {"/api/mode", true, N::kControl, true, true, [](Api& a, const Call& c) { return a.post_mode(c); },
     "idle (stop) or park"},
    command_route<command::Id::kReset>("/api/reset"),
    command_route<command::Id::kSpeed>("/api/speed"),
    {"/api/settings", true, N::kControl, true, true,
     [](Api& a, const Call& c) {
       a.post_settings(c.request.body, c.out, c.options, c.caller);
       return O::kDone;
     },
     "change settings (partial), saved"},
    {"/api/settings/reset", true, N::kAdmin, true, true,
     [](Api& a, const Call& c) {
       a.reset_settings(c.out, c.options);
       return O::kDone;
     },
     "every setting back to its default (not the password or tokens)"},
    {"/api/reboot", true, N::kControl, true, true,
     [](Api& a, const Call& c) { return a.post_reboot(c); }, "restart the controller"},
    // Set-up (setup_api.cpp, docs/commissioning.md).
    {"/api/setup", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.get_setup(c); },
     "whether any setting was saved (the set-up page is offered when not)"},
    {"/api/models", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.get_models(c); },
     "the rotator models, each figure with its source"},
    {"/api/setup/model", true, N::kControl, true, true,
     [](Api& a, const Call& c) { return a.post_model(c); },
     "fill the settings from a model's published figures, saved"},
    {"/api/commission", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.get_commission(c); },
     "self-commissioning: state, measurements, proposal, evidence"},
    {"/api/commission", true, N::kControl, true, true,
     [](Api& a, const Call& c) { return a.post_commission(c); },
     "start self-commissioning of an axis (a step, or all)"},
    {"/api/commission/accept", true, N::kControl, true, true,
     [](Api& a, const Call& c) { return a.post_commission_accept(c); },
     "write the proposed settings, saved"},
    {"/api/login", true, N::kPublic, false, true,
     [](Api& a, const Call& c) { return a.login(c.request, c.out, c.options, c.peer); },
     "log in with the web password: a session cookie"},
    {"/api/logout", true, N::kPublic, false, true,
     [](Api& a, const Call& c) {
       a.logout(c.caller, c.out, c.options);
       return O::kDone;
     },
     "end the session"},
    {"/api/password", true, N::kAdmin, false, true,
     [](Api& a, const Call& c) {
       return a.set_password(c.request, c.out, c.options, c.caller, c.peer);
     },
     "set, change or clear the web password"},
    {"/api/tokens", true, N::kAdmin, false, true,
     [](Api& a, const Call& c) {
       a.create_token(c.request, c.out, c.options);
       return O::kDone;
     },
     "make a bearer token (shown once)"},
    {"/api/tokens/revoke", true, N::kAdmin, false, true,
     [](Api& a, const Call& c) {
       a.revoke_token(c.request, c.out, c.options);
       return O::kDone;
     },
     "revoke a bearer token"},
    {"/api/lock", true, N::kControl, false, true,
     [](Api& a, const Call& c) {
       a.lock(c.request, c.out, c.options, c.caller);
       return O::kDone;
     },
     "take the control lock for N minutes"},
    {"/api/unlock", true, N::kControl, false, true,
     [](Api& a, const Call& c) {
       a.unlock(c.caller, c.out, c.options);
       return O::kDone;
     },
     "release the control lock"},    // Tracking (track_api.cpp): the handler tells the methods apart and
    // checks the bodies (PUT /api/tle takes the TLE text as it is: another
    // site's form cannot send a PUT).
    {"/api/tle", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.run_track(c); }, "the stored TLEs"},
    {"/api/tle", true, N::kControl, true, false,
     [](Api& a, const Call& c) { return a.run_track(c); },
     "PUT: store TLEs (a paste, all or nothing); DELETE ?object=: remove one", "PUT DELETE"},
    {"/api/passes", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.run_track(c); },
     "the next passes of an object, the Sun or the Moon"},
    {"/api/track", false, N::kRead, false, false,
     [](Api& a, const Call& c) { return a.run_track(c); }, "the tracking mode's state and plan"},
    {"/api/track", true, N::kControl, true, false,
     [](Api& a, const Call& c) { return a.run_track(c); },
     "POST: track an object, the Sun, the Moon or az/el; DELETE: end the track", "POST DELETE"},
    // Where the beam points (place_api.cpp, preset_api.cpp).
    {"/api/place", false, N::kRead, false, false, get_place,
     "the bearing and distance to a locator or lat/lon (no move)"},
    command_route<command::Id::kPlace>("/api/place"),
    {"/api/sky", false, N::kRead, false, false, get_sky,
     "the station, the beamwidth, the Sun's and the Moon's positions (the map)"},
    {"/api/presets", false, N::kRead, false, false, get_presets, "the named headings"},
    {"/api/presets", true, N::kControl, true, true, post_presets,
     "add or replace a named heading (16 at most), saved"},
    {"/api/presets/delete", true, N::kControl, true, true, delete_preset, "remove a named heading"},
    command_route<command::Id::kPreset>("/api/preset"),
    {"/api/odometer", false, N::kRead, false, false, get_odometer, "the wear odometer"},
    {"/api/odometer/reset", true, N::kControl, true, true, post_odometer_reset,
     "reset the wear odometer, dated"},
};

std::span<const Api::Route> Api::routes() {
  return kRoutes;
}

bool Api::takes_method(const Route& route, std::string_view method) {
  if (route.verbs.empty()) return method == "POST";
  std::string_view rest = route.verbs;
  while (!rest.empty()) {
    const std::size_t space = rest.find(' ');
    if (text::slice(rest, 0, space) == method) return true;
    rest = space == std::string_view::npos ? std::string_view{} : text::slice(rest, space + 1);
  }
  return false;
}

Api::Outcome Api::handle(const HttpRequest& request, protocol::ByteSink& out,
                         const ResponseOptions& options, const access::Peer& peer) {
  const std::string_view path = request.path;
  // PUT and DELETE change state as POST does (the tracking routes).
  const bool is_post = request.method == Method::kPost || request.method == Method::kPut ||
                       request.method == Method::kDelete;
  const bool is_get = request.method == Method::kGet || request.method == Method::kHead;
  bool allows_get = false;
  bool allows_post = false;
  const Route* route = nullptr;
  for (const Route& r : kRoutes) {
    if (path != r.path) continue;
    (r.post ? allows_post : allows_get) = true;
    if (r.post == is_post) route = &r;
  }
  if (!allows_get && !allows_post) {
    send_error(out, 404, "no such API endpoint", options);
    return Outcome::kDone;
  }
  if ((is_post && !allows_post) || (is_get && !allows_get) || (!is_post && !is_get)) {
    ResponseOptions o = options;
    o.extra_headers = allows_get && allows_post ? "Allow: GET, HEAD, POST\r\n"
                      : allows_get              ? "Allow: GET, HEAD\r\n"
                                                : "Allow: POST\r\n";
    send_error(out, 405, "method not allowed here", o);
    return Outcome::kDone;
  }

  // Access control (docs/security.md).
  const Caller caller = auth_.identify(request, settings(), transport_now_);
  last_caller_ = caller;
  if (WebAuth::enabled(settings()) && route->need != Need::kPublic) {
    ResponseOptions o = options;
    o.extra_headers = "WWW-Authenticate: Bearer realm=\"rotord\"\r\n";
    if (ctx_.crypto == nullptr) {
      send_error(out, 503, "a web password is set but this build has no cryptography", options);
      return Outcome::kDone;
    }
    if (caller.kind == Caller::Kind::kBadToken) {
      count_auth_failure(false);
      char address[16];
      auth_.refused(peer, "rotord: unknown bearer token from %s refused", peer_text(peer, address));
      send_error(out, 401, "unknown or revoked token", o);
      return Outcome::kDone;
    }
    if (!caller.may_read()) {
      count_auth_failure(false);
      send_error(out, 401, "log in first (POST /api/login) or send a bearer token", o);
      return Outcome::kDone;
    }
    if (route->need == Need::kControl && !caller.may_control()) {
      count_auth_failure(false);
      send_error(out, 403, "this token is read-only", options);
      return Outcome::kDone;
    }
    if (route->need == Need::kAdmin && !caller.may_administer()) {
      count_auth_failure(false);
      send_error(out, 403, "tokens cannot do this: it needs the web login", options);
      return Outcome::kDone;
    }
  }
  // The unreadable access settings and the control lock: the command
  // layer's gate, the same for every route and every front end.
  if (const command::Result r =
          commands_.admit({route->need, route->locked, route->post}, authority(caller));
      !r.ok()) {
    if (r.status == command::Status::kLocked) count_auth_failure(false);
    send_result(out, options, r);
    return Outcome::kDone;
  }
  // A state-changing row takes POST, or the methods it names (verbs).
  if (route->post && !takes_method(*route, request.method_text)) {
    char allow[64];
    std::snprintf(allow, sizeof allow, "Allow: %s%.*s\r\n", allows_get ? "GET, HEAD, " : "",
                  static_cast<int>(route->verbs.empty() ? 4 : route->verbs.size()),
                  route->verbs.empty() ? "POST" : route->verbs.data());
    for (char* c = allow; *c != '\0'; ++c)
      if (*c == ' ' && c[-1] != ',' && c[-1] != ':') *c = ',';  // "PUT DELETE" -> "PUT,DELETE"
    ResponseOptions o = options;
    o.extra_headers = allow;
    send_error(out, 405, "method not allowed here", o);
    return Outcome::kDone;
  }
  // A POST body must be JSON, declared as such: a cross-site HTML form or
  // no-cors fetch cannot send that header, so another web page open in the
  // same browser cannot move the antenna.
  if (route->post && route->json_body && !request.json_body) {
    send_error(out, 415, "send Content-Type: application/json", options);
    return Outcome::kDone;
  }
  return route->run(*this, Call{request, out, options, caller, peer});
}

Api::Outcome Api::get_status(const Call& call) {
  send_json(call.out, 200, call.options, [this](JsonWriter& w) { write_status(w); });
  return Outcome::kDone;
}

Api::Outcome Api::get_station(const Call& call) {
  if (station_ == nullptr) {
    // 200, not 404: the station page asks for this, and a page that meets a
    // 404 shows an error in the browser's console for a setting left off.
    send_json(call.out, 200, call.options, [](JsonWriter& w) {
      w.begin_object()
          .member("available", false)
          .member("reason",
                  "no station here: MQTT is off (mqtt.enabled), or this is a Pico W (a Linux "
                  "rotord on the same broker shows the station)")
          .key("rotators")
          .begin_array()
          .end_array()
          .end_object();
    });
  } else {
    send_json(call.out, 200, call.options, [this](JsonWriter& w) { station_->write_station(w); });
  }
  return Outcome::kDone;
}

Api::Outcome Api::get_events(const Call& call) {
  if (call.request.method == Method::kHead) {
    write_head(call.out, 200, "text/event-stream", -1, {false, true, {}});
    return Outcome::kClose;
  }
  // The stream ends when the connection closes: no length, no keep-alive.
  write_head(call.out, 200, "text/event-stream", -1, {false, false, "Cache-Control: no-store\r\n"});
  return Outcome::kStartEvents;
}

Api::Outcome Api::get_schema(const Call& call) {
  send_json(call.out, 200, call.options, [this](JsonWriter& w) {
    write_settings_schema(ctx_.defaults != nullptr ? *ctx_.defaults : settings::Settings(), w,
                          settings::platform_name(ctx_.platform));
  });
  return Outcome::kDone;
}

Api::Outcome Api::post_mode(const Call& call) {
  // A REST alias: "idle" is STOP, "park" the park command.
  command::Member m[] = {{"mode", JsonType::kString}};
  if (const command::Result bad = command::read_members(call.request.body, m); !bad.ok()) {
    send_result(call.out, call.options, bad);
    return Outcome::kDone;
  }
  const std::string_view mode = m[0].value.text;
  const command::Request request{authority(call.caller), call.peer, {}};
  if (!m[0].present) {
    send_error(call.out, 400, "give mode: idle or park", call.options);
  } else if (mode == "idle" || mode == "park") {
    send_result(
        call.out, call.options,
        commands_.execute(mode == "idle" ? command::Id::kStop : command::Id::kPark, request));
  } else if (mode == "goto" || mode == "manual") {
    send_error(call.out, 422, "goto and manual start with POST /api/goto and /api/move",
               call.options);
  } else {
    send_error(call.out, 422, "mode must be idle or park", call.options);
  }
  return Outcome::kDone;
}

Api::Outcome Api::post_reboot(const Call& call) {
  if (ctx_.reboot == nullptr || !ctx_.reboot->request_reboot()) {
    send_error(call.out, 501, "this port cannot restart the controller", call.options);
    return Outcome::kDone;
  }
  ResponseOptions o = call.options;
  o.keep_alive = false;
  send_json(call.out, 202, o, [](JsonWriter& w) {
    w.begin_object().member("ok", true).member("rebooting", true).end_object();
  });
  return Outcome::kClose;
}

void Api::get_settings(protocol::ByteSink& out, const ResponseOptions& options) {
  const settings::Settings& values = ctx_.controller.settings();
  send_json(out, 200, options, [&](JsonWriter& w) { write_settings(values, w); });
}

void Api::post_settings(std::string_view body, protocol::ByteSink& out,
                        const ResponseOptions& options, const Caller& caller) {
  settings::Settings& values = ctx_.controller.settings();
  if (WebAuth::enabled(values) && !caller.may_administer()) {
    // A control token changes the rotator's settings, never the access
    // rules or a secret: it cannot widen its own rights.
    JsonObjectReader reader(body);
    std::string_view key;
    JsonValue value;
    while (reader.valid() && reader.next(key, value)) {
      const std::optional<Id> id = settings::find(key);
      if (id && !settings::line_writable(*id)) {
        count_auth_failure(false);
        char message[128];
        std::snprintf(message, sizeof message, "%s needs the web login, not a token",
                      settings::def(*id).key);
        send_error(out, 403, message, options);
        return;
      }
    }
  }
  backup_ = values;
  const ApplyOutcome r = apply_settings_json(body, values, scratch_, errors_, true);
  if (r.status == ApplyOutcome::kBadJson) {
    char message[160];
    std::snprintf(message, sizeof(message), "invalid JSON: %s", r.message);
    send_error(out, 400, message, options);
    return;
  }
  if (r.status == ApplyOutcome::kInvalid) {
    send_json(out, 422, options, [&](JsonWriter& w) {
      w.begin_object().member("error", r.message).key("errors").begin_object();
      for (std::size_t n = 0; n < errors_.size(); ++n) w.member(errors_[n].key, errors_[n].reason);
      w.end_object().end_object();
    });
    return;
  }
  if (r.changed.any() && !persist(out, options)) {
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (r.changed[n]) values.copy_value(static_cast<Id>(n), backup_);
    return;
  }
  send_changed(out, options, r.changed);
}

void Api::reset_settings(protocol::ByteSink& out, const ResponseOptions& options) {
  settings::Settings& values = ctx_.controller.settings();
  if (ctx_.defaults != nullptr) {
    scratch_ = *ctx_.defaults;
  } else {
    scratch_.reset_to_defaults();
  }
  const settings::Settings& defaults = scratch_;
  backup_ = values;
  SettingSet changed;
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    // The web password and the tokens stay: a reset must not open the
    // controller to everyone (POST /api/password with "" does that).
    if ((settings::def(id).flags & settings::kHidden) != 0) continue;
    if (!values.same_value(id, defaults)) {
      changed[n] = true;
      values.copy_value(id, defaults);
    }
  }
  if (changed.any() && !persist(out, options)) {
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (changed[n]) values.copy_value(static_cast<Id>(n), backup_);
    return;
  }
  send_changed(out, options, changed);
}

bool Api::save() {
  if (ctx_.storage == nullptr) return true;
  // Only the user's layer over the defaults is stored (settings_layers.hpp).
  // scratch_ is free again here: post and reset are done with it.
  if (ctx_.defaults == nullptr) scratch_.reset_to_defaults();
  const settings::Settings& base = ctx_.defaults != nullptr ? *ctx_.defaults : scratch_;
  return save_settings(*ctx_.storage, ctx_.controller.settings(), base, document_,
                       sizeof(document_));
}

bool Api::persist(protocol::ByteSink& out, const ResponseOptions& options) {
  if (save()) return true;
  send_error(out, 500, "the settings could not be saved; nothing was changed", options);
  return false;
}

void Api::send_changed(protocol::ByteSink& out, const ResponseOptions& options,
                       const SettingSet& changed) {
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object().member("ok", true).member("saved", ctx_.storage != nullptr);
    w.key("changed").begin_array();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (changed[n]) w.string(settings::def(static_cast<Id>(n)).key);
    w.end_array().key("restart_required").begin_array();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (changed[n] && (settings::def(static_cast<Id>(n)).flags & settings::kRestart))
        w.string(settings::def(static_cast<Id>(n)).key);
    w.end_array().end_object();
  });
}

}  // namespace rotord::web
