#pragma once
#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "command/commands.hpp"
#include "command/settings_commands.hpp"
#include "command/system_commands.hpp"
#include "hal/clock_sync.hpp"
#include "hal/storage.hpp"
#include "hal/wall_clock.hpp"
#include "json/settings_json.hpp"
#include "metrics/registry.hpp"
#include "rotator/controller.hpp"
#include "settings/applies.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/tle_catalog.hpp"
#include "web/http_request.hpp"
#include "web/http_response.hpp"
#include "web/station_source.hpp"
#include "web/web_auth.hpp"

namespace rotord::web {

struct ApiContext {
  Controller& controller;
  /// Where POST /api/settings persists; nullptr keeps settings in RAM only.
  hal::Storage* storage = nullptr;
  /// What POST /api/settings/reset restores and the schema reports as the
  /// defaults: the table's defaults plus what the port's hardware profile sets.
  const settings::Settings* defaults = nullptr;
  /// POST /api/reboot (command/system_commands.hpp); nullptr: 501.
  command::SystemHooks* reboot = nullptr;
  const char* version = "";
  /// GET /api/status time_utc; nullptr or an unknown time: null.
  const hal::WallClock* wall_clock = nullptr;
  /// The host's own name (Linux: gethostname), a name the web may be reached
  /// by besides net.hostname (host_check.hpp); nullptr on the Pico W.
  const char* host_name = nullptr;
  /// What the port counts (connections, errors, ticks, saves) for GET
  /// /metrics and GET /healthz; nullptr: the controller's metrics only.
  /// Not const: the web's login and tokens count failures here
  /// (ProtocolCounters::on_auth_failure under metrics::Protocol::kHttp).
  metrics::Registry* metrics = nullptr;
  /// Access control's cryptography (access/crypto.hpp); nullptr: none, and
  /// a stored web password then refuses everything but STOP.
  access::Crypto* crypto = nullptr;
  /// PBKDF2 iterations of a new web password hash, and how many one slice
  /// runs (per Api::poll, or Api::work in the Pico's idle time).
  std::uint32_t pbkdf2_iterations = 100'000;
  std::uint32_t pbkdf2_slice = 10'000;
  /// Where logins, failed logins, tokens and the control lock are logged.
  protocol::ByteSink* log = nullptr;
  /// The process's log budget (access/log_gate.hpp), shared with the port's
  /// other lines; nullptr: the web's own.
  access::LogGate* log_gate = nullptr;
  /// The stored TLEs (GET/PUT /api/tle, POST /api/track) and where they are
  /// saved; nullptr: no store, /api/tle answers 501 (tracking the Sun, the
  /// Moon or a direction still works).
  tracking::TleCatalog* tles = nullptr;
  hal::Storage* tle_storage = nullptr;
  /// false (Pico W): PUT/DELETE /api/tle are refused while the rotator
  /// moves, as a flash write pauses the control loop for ~0.1 s.
  bool tle_save_while_moving = true;
  /// Target evaluations GET /api/passes may do within the request, and per
  /// poll() afterwards (the Pico W keeps both small: ~3 ms each).
  int passes_request_budget = 200000;
  int passes_poll_budget = 50;
  /// What reading the stored settings dropped at start-up (GET /api/status
  /// "settings_load", shown on the settings page); nullptr: nothing.
  const LoadReport* load_report = nullptr;
  /// What the firmware drives (GET /api/settings/schema "platform"): the
  /// settings form hides the other platforms' pins and lines.
  settings::Platform platform = settings::Platform::kUnknown;
  /// The clock's state in words (GET /api/setup "clock"); nullptr: not said.
  const hal::ClockSync* clock_sync = nullptr;
};

/// The REST API (docs/web_api.md) on the controller's command API. One per
/// controller, shared by every HTTP session: requests are handled one at a
/// time in the control loop's thread, so the scratch space below is shared
/// too (it would not fit the Pico's stack).
class Api {
 public:
  /// The stored settings document (json/settings_json.hpp).
  static constexpr std::size_t kMaxDocumentBytes = kMaxSettingsDocumentBytes;

  explicit Api(const ApiContext& context);

  const settings::Settings& settings() const { return ctx_.controller.settings(); }
  const char* host_name() const { return ctx_.host_name; }

  enum class Outcome : unsigned char { kDone, kStartEvents, kClose, kPending };

  /// Who may call a route once access control is on (web.password set):
  /// kPublic anyone, kRead a login or any token, kControl a login or a
  /// control token, kAdmin the web login only (command/commands.hpp).
  using Need = command::Need;
  /// What a route's handler is given.
  struct Call {
    const HttpRequest& request;
    protocol::ByteSink& out;
    const ResponseOptions& options;
    const Caller& caller;
    const access::Peer& peer;
  };
  /// One row of the REST API's route table (web_api.cpp). handle() finds the
  /// row, answers 404/405 and the access checks from it, then runs it; the
  /// endpoint table of docs/web_api.md is checked against these rows
  /// (tests/docs).
  struct Route {
    std::string_view path;
    bool post;  ///< POST; else GET (and HEAD)
    Need need;
    /// Refused (423) to all but the control lock's holder while it is held.
    bool locked;
    /// The body must be declared JSON (415 otherwise): a cross-site form
    /// cannot send that header. Only STOP takes anything: it must always work.
    bool json_body;
    Outcome (*run)(Api& api, const Call& call);
    std::string_view help;
    /// A state-changing row's methods when not POST, e.g. "PUT DELETE"
    /// (the tracking routes); empty: POST.
    std::string_view verbs = {};
  };
  static std::span<const Route> routes();
  /// Whether a state-changing row takes `method` ("POST", or its verbs).
  static bool takes_method(const Route& route, std::string_view method);
  /// Answers one request whose path starts with /api/, from `peer`.
  /// kStartEvents: the response head of an event stream went out and events
  /// follow (poll). kPending: a login or a new password is being hashed;
  /// the session asks finish_pending() on each poll until it answers.
  Outcome handle(const HttpRequest& request, protocol::ByteSink& out,
                 const ResponseOptions& options, const access::Peer& peer = {});

  /// The ticket of the request that just went kPending.
  std::uint32_t pending_ticket() const { return auth_.job().ticket; }
  /// Writes the pending request's response once its hash is done; false
  /// while it is still being computed.
  bool finish_pending(std::uint32_t ticket, protocol::ByteSink& out,
                      const ResponseOptions& options);
  /// The session of a pending request closed: its result is not waited for.
  void abandon_pending(std::uint32_t ticket);
  /// Whether a slow hash is being computed: the Pico's loop then calls
  /// work() in its idle time instead of sleeping.
  bool auth_busy() const {
    return auth_.job().kind != WebAuth::JobKind::kNone && !auth_.job().completed;
  }
  /// One more slice of the slow hash (the port's idle time).
  void work();

  /// Whether a page (not /api/) may be served: access control is off, the
  /// page is the login page's, or the caller logged in (or sent a token).
  bool page_allowed(const HttpRequest& request);
  /// Who sent the last request handle() answered (an event stream keeps it).
  const Caller& last_caller() const { return last_caller_; }
  /// Whether `caller` may still read: access control is off, or its
  /// session is still logged in, or its token still stored. An event stream
  /// ends when not (logout, expiry, a new password, a revoked token).
  bool still_allowed(const Caller& caller) const;

  /// GET /metrics (Prometheus text format) and GET /healthz; any other
  /// method answers 405 (web_api_observability.cpp).
  void handle_metrics(const HttpRequest& request, protocol::ByteSink& out,
                      const ResponseOptions& options);
  void handle_health(const HttpRequest& request, protocol::ByteSink& out,
                     const ResponseOptions& options);

  /// Called by the port on every pass of its loop with the transport's
  /// (wall) clock, whether or not a client is connected: a hold-to-move
  /// whose renewals stopped (page closed, network gone) stops then.
  void poll(Millis transport_now);

  /// The live state: GET /api/status and every event of /api/events.
  void write_status(JsonWriter& w) const;
  Controller& controller() { return ctx_.controller; }
  /// The command layer every command route (and MQTT) runs through.
  command::Commands& commands() { return commands_; }
  /// What `caller` was granted by the web's access control.
  command::Authority authority(const Caller& caller) const;
  WebAuth& auth() { return auth_; }
  /// Where the command layer stores a REST change before the answer (the
  /// settings routes; the presets, place_api.hpp).
  command::Store store();
  /// GET /api/station's data (the MQTT station); nullptr: 404.
  void set_station(const StationSource* station) { station_ = station; }

 private:
  /// A failed login (or a refused credential): counted by the access layer
  /// and, for GET /metrics, as an HTTP auth failure.
  void count_auth_failure(bool login) {
    if (login)
      auth_.count_failed_login();
    else
      auth_.count_refused();
    if (ctx_.metrics != nullptr) ctx_.metrics->protocol(metrics::Protocol::kHttp).on_auth_failure();
  }
  static const Route kRoutes[];
  /// handle()'s steps, each answering (and returning nullptr or false) when
  /// the request stops there: the route (404, 405), the caller's login or
  /// token (401, 403), the method and the body's type (405, 415).
  const Route* find_route(const HttpRequest& request, protocol::ByteSink& out,
                          const ResponseOptions& options, bool& allows_get);
  bool authenticate(const Route& route, Method method, const Caller& caller,
                    const access::Peer& peer, protocol::ByteSink& out,
                    const ResponseOptions& options);
  /// The command layer's gate for the route (503, 423). Not inlined: its
  /// Result stays off the stack while the route runs (the Pico W's 4 KB).
  __attribute__((noinline)) bool pass_gate(const Route& route, Method method, const Caller& caller,
                                           const access::Peer& peer, protocol::ByteSink& out,
                                           const ResponseOptions& options);
  bool takes_body(const Route& route, const HttpRequest& request, bool allows_get,
                  protocol::ByteSink& out, const ResponseOptions& options);

  // The live state (status_api.cpp); the REST aliases and reboot (web_api.cpp);
  // the commands themselves are the command layer's (command/commands.hpp).
  Outcome get_status(const Call& call);
  Outcome get_events(const Call& call);
  Outcome get_station(const Call& call);
  Outcome get_schema(const Call& call);
  Outcome post_mode(const Call& call);
  Outcome post_reboot(const Call& call);
  // Set-up (setup_api.cpp).
  Outcome get_setup(const Call& call);
  Outcome get_models(const Call& call);
  Outcome post_model(const Call& call);
  Outcome post_commission(const Call& call);
  Outcome get_commission(const Call& call);
  Outcome post_commission_accept(const Call& call);
  /// The answer to a settings write of the command layer: what changed
  /// (saved), or why nothing did (`refused_status` for a rejected value).
  Outcome send_set(const Call& call, const command::SetResult& r, int refused_status);

  void get_settings(protocol::ByteSink& out, const ResponseOptions& options);
  Outcome post_settings(const Call& call);
  Outcome reset_settings(const Call& call);
  /// Persists the settings, or restores `backup_` when that fails.
  bool persist(protocol::ByteSink& out, const ResponseOptions& options);
  /// Saves the settings; false (nothing answered) when that fails.
  bool save();

  // Access control's endpoints (auth_api.cpp: login, password; token_api.cpp:
  // tokens, the lock).
  Outcome login(const HttpRequest& request, protocol::ByteSink& out, const ResponseOptions& options,
                const access::Peer& peer);
  void logout(const Caller& caller, protocol::ByteSink& out, const ResponseOptions& options);
  Outcome set_password(const HttpRequest& request, protocol::ByteSink& out,
                       const ResponseOptions& options, const Caller& caller,
                       const access::Peer& peer);
  void get_auth(const Caller& caller, protocol::ByteSink& out, const ResponseOptions& options);
  void get_tokens(protocol::ByteSink& out, const ResponseOptions& options);
  void create_token(const HttpRequest& request, protocol::ByteSink& out,
                    const ResponseOptions& options);
  void revoke_token(const HttpRequest& request, protocol::ByteSink& out,
                    const ResponseOptions& options);
  void lock(const HttpRequest& request, protocol::ByteSink& out, const ResponseOptions& options,
            Caller caller);
  void unlock(const Caller& caller, protocol::ByteSink& out, const ResponseOptions& options);
  // Tracking's endpoints (track_api.cpp, tle_api.cpp, passes_api.cpp).
  void handle_track(const HttpRequest& request, protocol::ByteSink& out,
                    const ResponseOptions& options, const access::Peer& peer);
  Outcome run_track(const Call& call) {
    handle_track(call.request, call.out, call.options, call.peer);
    return Outcome::kDone;
  }
  void get_tles(protocol::ByteSink& out, const ResponseOptions& options);
  void put_tles(const HttpRequest& request, protocol::ByteSink& out, const ResponseOptions& options,
                const access::Peer& peer);
  void delete_tle(const HttpRequest& request, protocol::ByteSink& out,
                  const ResponseOptions& options, const access::Peer& peer);
  void get_passes(const HttpRequest& request, protocol::ByteSink& out,
                  const ResponseOptions& options);
  void post_track(const HttpRequest& request, protocol::ByteSink& out,
                  const ResponseOptions& options, const access::Peer& peer);
  void write_track(JsonWriter& w) const;
  /// Starts the search GET /api/passes asks for; false when refused (answered).
  bool start_pass_search(const char* object, int hours, double min_el, std::int64_t utc_ms,
                         protocol::ByteSink& out, const ResponseOptions& options);
  /// Continues a pass search GET /api/passes began (poll()).
  void work_passes(int evaluations);

  /// Acts on a computed slow hash: a login's session, a password's storage.
  void complete_job();
  void fail_login(WebAuth::Job& job, const char* who);
  void complete_login(WebAuth::Job& job, const char* who);
  void complete_password(WebAuth::Job& job, const char* who);
  /// The lock's state: {"held", "mine", "by", "remaining_s"}.
  void write_lock(JsonWriter& w, const Caller* caller) const;
  /// 423 with the lock's holder and time left (the command layer's words).
  void send_locked(protocol::ByteSink& out, const ResponseOptions& options);

  ApiContext ctx_;
  WebAuth auth_;
  command::Commands commands_;
  const StationSource* station_ = nullptr;
  Caller last_caller_;
  Millis transport_now_ = 0;
  settings::Settings scratch_;
  settings::Settings backup_;
  SettingErrors errors_;
  char document_[kMaxDocumentBytes];  ///< also the TLE store's text when saving it
  /// GET /api/passes: one search at a time, its passes kept until another
  /// object, window or horizon is asked for (or a minute has passed).
  struct PassSearch {
    static constexpr std::size_t kMaxPasses = 16;
    bool active = false;  ///< searching (step() still to be called)
    bool valid = false;   ///< the key below describes the search
    char key[40] = {};    ///< object, as asked
    int hours = 0;
    double min_el_deg = 0;
    std::int64_t from_ms = 0;
    tracking::SkyTarget target;
    tracking::PassFinder finder;
    tracking::Pass passes[kMaxPasses];
    std::size_t count = 0;
    tracking::Sgp4Error error = tracking::Sgp4Error::kOk;
  } passes_;
};

}  // namespace rotord::web
