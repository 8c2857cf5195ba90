#pragma once
#include <array>
#include <cstddef>

#include "hal/storage.hpp"
#include "hal/wall_clock.hpp"
#include "metrics/registry.hpp"
#include "rotator/controller.hpp"
#include "web/http_request.hpp"
#include "web/http_response.hpp"
#include "web/settings_json.hpp"

namespace rotord::web {

/// What a port does for POST /api/reboot (Linux: re-create the controller in
/// process; Pico: watchdog reset). Called while a request is being handled, so
/// the port must act later, after the response has gone out.
class RebootHook {
 public:
  virtual ~RebootHook() = default;
  virtual bool request_reboot() = 0;
};

struct ApiContext {
  Controller& controller;
  /// Where POST /api/settings persists; nullptr keeps settings in RAM only.
  hal::Storage* storage = nullptr;
  /// What POST /api/settings/reset restores and the schema reports as the
  /// defaults: the table's defaults plus what the port's hardware profile sets.
  const settings::Settings* defaults = nullptr;
  RebootHook* reboot = nullptr;  ///< nullptr: POST /api/reboot answers 501
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
};

/// The REST API (docs/web_api.md) on the controller's command API. One per
/// controller, shared by every HTTP session: requests are handled one at a
/// time in the control loop's thread, so the scratch space below is shared
/// too (it would not fit the Pico's stack).
class Api {
 public:
  static constexpr Millis kDefaultHoldMs = 1000;
  static constexpr Millis kMinHoldMs = 100;
  static constexpr Millis kMaxHoldMs = 10000;
  /// The stored settings document (pretty-printed), with room to grow.
  static constexpr std::size_t kMaxDocumentBytes = 7168;

  explicit Api(const ApiContext& context) : ctx_(context) {}

  const settings::Settings& settings() const { return ctx_.controller.settings(); }
  const char* host_name() const { return ctx_.host_name; }

  enum class Outcome : unsigned char { kDone, kStartEvents, kClose };
  /// Answers one request whose path starts with /api/. kStartEvents: the
  /// response head of an event stream went out and events follow (poll).
  Outcome handle(const HttpRequest& request, protocol::ByteSink& out,
                 const ResponseOptions& options);

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

 private:
  void get_settings(protocol::ByteSink& out, const ResponseOptions& options);
  void post_settings(std::string_view body, protocol::ByteSink& out,
                     const ResponseOptions& options);
  void reset_settings(protocol::ByteSink& out, const ResponseOptions& options);
  /// Persists the settings, or restores `backup_` when that fails.
  bool persist(protocol::ByteSink& out, const ResponseOptions& options);
  void send_changed(protocol::ByteSink& out, const ResponseOptions& options,
                    const SettingSet& changed);

  /// Hold-to-move's dead-man per axis, on the transport's clock: hold_ms is
  /// the client's time, whatever `--speedup` or `--clock manual` does to
  /// controller time.
  struct DeadMan {
    bool armed = false;
    Millis until = 0;
  };
  void arm_dead_man(AxisId axis, Millis hold_ms);

  ApiContext ctx_;
  Millis transport_now_ = 0;
  std::array<DeadMan, 2> dead_man_{};
  settings::Settings scratch_;
  settings::Settings backup_;
  SettingErrors errors_;
  char document_[kMaxDocumentBytes];
};

}  // namespace rotord::web
