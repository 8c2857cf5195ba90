#include "web/web_api.hpp"

#include <cstdio>

#include "command/json_args.hpp"
#include "json/json_reader.hpp"
#include "util/slice.hpp"
#include "web/care_api.hpp"
#include "web/place_api.hpp"
#include "web/route_log.hpp"
#include "web/wind_api.hpp"

namespace rotord::web {
namespace {

using settings::Id;

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
  const command::Request request{api.authority(call.caller), call.peer, call.request.body, "rest"};
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
                            context.log, context.log_gate}),
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
     [](Api& a, const Call& c) { return a.post_settings(c); }, "change settings (partial), saved"},
    {"/api/settings/reset", true, N::kAdmin, true, true,
     [](Api& a, const Call& c) { return a.reset_settings(c); },
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
    {"/api/wind/override", true, N::kControl, true, true, post_wind_override,
     "override a wind stow for a time ({\"minutes\": n}), or end the override ({\"end\": true})"},
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

const Api::Route* Api::find_route(const HttpRequest& request, protocol::ByteSink& out,
                                  const ResponseOptions& options, bool& allows_get) {
  // PUT and DELETE change state as POST does (the tracking routes).
  const bool is_post = request.method == Method::kPost || request.method == Method::kPut ||
                       request.method == Method::kDelete;
  const bool is_get = request.method == Method::kGet || request.method == Method::kHead;
  allows_get = false;
  bool allows_post = false;
  const Route* route = nullptr;
  for (const Route& r : kRoutes) {
    if (request.path != r.path) continue;
    (r.post ? allows_post : allows_get) = true;
    if (r.post == is_post) route = &r;
  }
  if (!allows_get && !allows_post) {
    send_error(out, 404, "no such API endpoint", options);
    return nullptr;
  }
  if ((is_post && !allows_post) || (is_get && !allows_get) || (!is_post && !is_get)) {
    ResponseOptions o = options;
    o.extra_headers = allows_get && allows_post ? "Allow: GET, HEAD, POST\r\n"
                      : allows_get              ? "Allow: GET, HEAD\r\n"
                                                : "Allow: POST\r\n";
    send_error(out, 405, "method not allowed here", o);
    return nullptr;
  }
  return route;
}

bool Api::authenticate(const Route& route, Method method, const Caller& caller,
                       const access::Peer& peer, protocol::ByteSink& out,
                       const ResponseOptions& options) {
  if (!WebAuth::enabled(settings()) || route.need == Need::kPublic) return true;
  ResponseOptions o = options;
  o.extra_headers = "WWW-Authenticate: Bearer realm=\"rotord\"\r\n";
  if (ctx_.crypto == nullptr) {
    send_error(out, 503, "a web password is set but this build has no cryptography", options);
    return false;
  }
  if (caller.kind == Caller::Kind::kBadToken) {
    count_auth_failure(false);
    char address[access::kAddressTextBytes];
    auth_.refused(peer, "rotord: unknown bearer token from %s refused",
                  access::peer_text(peer, address));
    send_error(out, 401, "unknown or revoked token", o);
    return false;
  }
  const char* refusal = nullptr;
  int status = 403;
  if (!caller.may_read()) {
    refusal = "log in first (POST /api/login) or send a bearer token";
    status = 401;
  } else if (route.need == Need::kControl && !caller.may_control()) {
    refusal = "this token is read-only";
  } else if (route.need == Need::kAdmin && !caller.may_administer()) {
    refusal = "tokens cannot do this: it needs the web login";
  }
  if (refusal == nullptr) return true;
  told_refused(ctx_.controller, route, method, peer, "DENIED");
  count_auth_failure(false);
  send_error(out, status, refusal, status == 401 ? o : options);
  return false;
}

bool Api::takes_body(const Route& route, const HttpRequest& request, bool allows_get,
                     protocol::ByteSink& out, const ResponseOptions& options) {
  if (!route.post) return true;
  // A state-changing row takes POST, or the methods it names (verbs).
  if (!takes_method(route, request.method_text)) {
    char allow[64];
    std::snprintf(allow, sizeof allow, "Allow: %s%.*s\r\n", allows_get ? "GET, HEAD, " : "",
                  static_cast<int>(route.verbs.empty() ? 4 : route.verbs.size()),
                  route.verbs.empty() ? "POST" : route.verbs.data());
    for (char* c = allow; *c != '\0'; ++c)
      if (*c == ' ' && c[-1] != ',' && c[-1] != ':') *c = ',';  // "PUT DELETE" -> "PUT,DELETE"
    ResponseOptions o = options;
    o.extra_headers = allow;
    send_error(out, 405, "method not allowed here", o);
    return false;
  }
  // A POST body must be JSON, declared as such: a cross-site HTML form or
  // no-cors fetch cannot send that header, so another web page open in the
  // same browser cannot move the antenna.
  if (route.json_body && !request.json_body) {
    send_error(out, 415, "send Content-Type: application/json", options);
    return false;
  }
  return true;
}

bool Api::pass_gate(const Route& route, Method method, const Caller& caller,
                    const access::Peer& peer, protocol::ByteSink& out,
                    const ResponseOptions& options) {
  const command::Result r =
      commands_.admit({route.need, route.locked, route.post}, authority(caller));
  if (r.ok()) return true;
  told_refused(ctx_.controller, route, method, peer, command::status_word(r.status));
  if (r.status == command::Status::kLocked) count_auth_failure(false);
  send_result(out, options, r);
  return false;
}

Api::Outcome Api::handle(const HttpRequest& request, protocol::ByteSink& out,
                         const ResponseOptions& options, const access::Peer& peer) {
  bool allows_get = false;
  const Route* route = find_route(request, out, options, allows_get);
  if (route == nullptr) return Outcome::kDone;
  // Access control (docs/security.md).
  const Caller caller = auth_.identify(request, settings(), transport_now_);
  last_caller_ = caller;
  if (!authenticate(*route, request.method, caller, peer, out, options)) return Outcome::kDone;
  // The unreadable access settings and the control lock: the command
  // layer's gate, the same for every route and every front end.
  if (!pass_gate(*route, request.method, caller, peer, out, options)) return Outcome::kDone;
  if (!takes_body(*route, request, allows_get, out, options)) return Outcome::kDone;
  return route->run(*this, Call{request, out, options, caller, peer});
}

Api::Outcome Api::post_mode(const Call& call) {
  // A REST alias: "idle" is STOP, "park" the park command.
  command::Member m[] = {{"mode", JsonType::kString}};
  if (command::Result bad; !command::read_members(call.request.body, m, bad)) {
    send_result(call.out, call.options, bad);
    return Outcome::kDone;
  }
  const std::string_view mode = m[0].value.text;
  const command::Request request{authority(call.caller), call.peer, {}, "rest"};
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
  if (!command::reboot(ctx_.controller, {"rest", call.peer}, ctx_.reboot).ok()) {
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

}  // namespace rotord::web
