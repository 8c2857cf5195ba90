// The tracking endpoints of the REST API (docs/web_api.md#tracking): the
// stored TLEs, passes, and the tracking mode. Gating (who may call what) is
// in web_api.cpp's route table; each handler here checks its own methods.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "command/care_commands.hpp"
#include "json/json_reader.hpp"
#include "tracking/julian.hpp"
#include "util/slice.hpp"
#include "web/query.hpp"
#include "web/track_json.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
using tracking::TargetKind;

void write_utc(JsonWriter& w, std::string_view name, std::int64_t unix_ms) {
  char text[32];
  const std::size_t n = tracking::format_utc_seconds(unix_ms, text, sizeof text);
  w.key(name);
  if (n > 0) {
    w.string(std::string_view(text, n));
  } else {
    w.null();
  }
}

void write_pass(JsonWriter& w, const tracking::Pass& p) {
  w.begin_object();
  write_utc(w, "aos_utc", p.aos_ms);
  write_utc(w, "los_utc", p.los_ms);
  write_utc(w, "max_el_utc", p.max_el_ms);
  w.member("max_el_deg", p.max_el_deg)
      .member("aos_az_deg", p.aos_az_deg)
      .member("los_az_deg", p.los_az_deg)
      .member("max_el_az_deg", p.max_el_az_deg)
      .member("max_az_rate_deg_s", p.max_az_rate_deg_s)
      .member("max_el_rate_deg_s", p.max_el_rate_deg_s)
      .member("aos_clipped", p.aos_clipped)
      .member("los_clipped", p.los_clipped)
      .end_object();
}

namespace {

const char* kind_name(TargetKind kind) {
  switch (kind) {
    case TargetKind::kSatellite:
      return "satellite";
    case TargetKind::kSun:
      return "sun";
    case TargetKind::kMoon:
      return "moon";
    case TargetKind::kNone:
      break;
  }
  return "fixed";
}

}  // namespace

void Api::handle_track(const HttpRequest& request, protocol::ByteSink& out,
                       const ResponseOptions& options, const access::Peer& peer) {
  const std::string_view path = request.path;
  const Method m = request.method;
  const bool get = m == Method::kGet || m == Method::kHead;
  auto refuse = [&](const char* allow) {
    ResponseOptions o = options;
    o.extra_headers = allow;
    send_error(out, 405, "method not allowed here", o);
  };
  if (path == "/api/tle") {
    if (get) return get_tles(out, options);
    if (!ctx_.tle_save_while_moving && ctx_.controller.status().moving())
      return send_error(out, 409, "the rotator is moving: store TLEs while it stands", options);
    if (m == Method::kPut) return put_tles(request, out, options, peer);
    if (m == Method::kDelete) return delete_tle(request, out, options, peer);
    return refuse("Allow: GET, HEAD, PUT, DELETE\r\n");
  }
  if (path == "/api/passes") {
    if (get) return get_passes(request, out, options);
    return refuse("Allow: GET, HEAD\r\n");
  }
  // /api/track
  if (get) {
    send_json(out, 200, options, [this](JsonWriter& w) { write_track(w); });
    return;
  }
  if (m == Method::kPost) return post_track(request, out, options, peer);
  if (m == Method::kDelete) {
    command::end_track(ctx_.controller, {"rest", peer});
    send_json(out, 200, options, [this](JsonWriter& w) { write_track(w); });
    return;
  }
  refuse("Allow: GET, HEAD, POST, DELETE\r\n");
}

namespace {

/// POST /api/track's body: one target (object, body or az/el) and when.
struct TrackBody {
  char object[40] = {};
  char body[8] = {};
  char when[8] = {};
  bool have_az = false, have_el = false;
  double az = 0, el = 0;
};

/// Reads the members; nullptr, or why not (with its status).
const char* read_track_body(std::string_view text, TrackBody& b, int& status, char* why,
                            std::size_t cap) {
  JsonObjectReader reader(text.empty() ? std::string_view("{}") : text);
  status = 400;
  if (!reader.valid()) {
    std::snprintf(why, cap, "invalid JSON: %s", reader.error());
    return why;
  }
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    char* field =
        key == "object" ? b.object : (key == "body" ? b.body : (key == "when" ? b.when : nullptr));
    const std::size_t field_cap =
        key == "object" ? sizeof b.object : (key == "body" ? sizeof b.body : sizeof b.when);
    if (field != nullptr) {
      if (value.type != JsonType::kString) return "object, body and when are strings";
      if (value.truncated || value.text.size() >= field_cap) {
        status = 422;
        return "object, body or when is too long";
      }
      std::memcpy(field, value.text.data(), value.text.size());
      field[value.text.size()] = '\0';
    } else if (key == "az" || key == "el") {
      if (value.type != JsonType::kNumber) return "az and el are numbers";
      (key == "az" ? b.have_az : b.have_el) = true;
      (key == "az" ? b.az : b.el) = value.number;
    } else {
      std::snprintf(why, cap, "unknown member '%.*s'",
                    static_cast<int>(key.size() > 40 ? 40 : key.size()), key.data());
      return why;
    }
  }
  return nullptr;
}

/// The controller's request for a body read; nullptr, or why not (with its status).
const char* track_request_of(const TrackBody& b, const tracking::TleCatalog* tles, TrackRequest& r,
                             int& status) {
  status = 400;
  const int targets = (b.object[0] != '\0') + (b.body[0] != '\0') + (b.have_az || b.have_el);
  if (targets != 1) return "give one of: object (a stored TLE), body (sun or moon), az/el";
  status = 422;
  if (b.when[0] == '\0' || std::strcmp(b.when, "next") == 0) {
    r.when = TrackWhen::kNextPass;
  } else if (std::strcmp(b.when, "now") == 0) {
    r.when = TrackWhen::kNow;
  } else {
    return "when must be now or next";
  }
  if (b.object[0] != '\0') {
    const tracking::TleCatalog::Entry* e = tles != nullptr ? tles->find(b.object) : nullptr;
    status = 404;
    if (e == nullptr) return "no such object stored (PUT /api/tle)";
    r.kind = TargetKind::kSatellite;
    tracking::TleCatalog::elements(*e, r.tle);
  } else if (b.body[0] != '\0') {
    if (std::strcmp(b.body, "sun") != 0 && std::strcmp(b.body, "moon") != 0)
      return "body must be sun or moon";
    r.kind = b.body[0] == 's' ? TargetKind::kSun : TargetKind::kMoon;
  } else {
    status = 400;
    if (!b.have_az) return "give az (and el) in degrees";
    r.kind = TargetKind::kNone;
    r.az_deg = static_cast<float>(b.az);
    r.el_deg = static_cast<float>(b.el);
  }
  return nullptr;
}

}  // namespace

void Api::post_track(const HttpRequest& request, protocol::ByteSink& out,
                     const ResponseOptions& options, const access::Peer& peer) {
  if (!request.json_body)
    return send_error(out, 415, "send Content-Type: application/json", options);
  TrackBody b;
  TrackRequest r;
  int status = 400;
  char why[120];
  const char* refusal = read_track_body(request.body, b, status, why, sizeof why);
  if (refusal == nullptr) refusal = track_request_of(b, ctx_.tles, r, status);
  if (refusal != nullptr) return send_error(out, status, refusal, options);
  const TrackError e = command::track(ctx_.controller, {"rest", peer}, r);
  if (e != TrackError::kOk) {
    const TrackStatus& t = ctx_.controller.track_status();
    char message[384];
    if (t.sgp4_error != tracking::Sgp4Error::kOk) {
      std::snprintf(message, sizeof message, "%s (%s)", track_error_text(e),
                    tracking::sgp4_error_name(t.sgp4_error));
    } else {
      std::snprintf(message, sizeof message, "%s", track_error_text(e));
    }
    return send_error(out, command::http_status(command::track_refusal(e)), message, options);
  }
  send_json(out, 200, options, [this](JsonWriter& w) { write_track(w); });
}

namespace {

/// The planned pass on the sky (for the Track page's polar plot): up to 60
/// points of azimuth and elevation.
void write_track_path(JsonWriter& w, const TrackStatus& t, const tracking::PassTable& table) {
  w.key("path").begin_array();
  if (t.planned && table.size() > 1) {
    const std::int64_t span = table.end_ms() - table.start_ms();
    for (int n = 0; n <= 60; ++n) {
      float u = 0, e = 0;
      table.at(table.start_ms() + span * n / 60, u, e);
      float a = u - 360.0f * static_cast<float>(static_cast<int>(u / 360.0f));
      if (a < 0) a += 360.0f;
      w.begin_array().number(static_cast<double>(a)).number(static_cast<double>(e)).end_array();
    }
  }
  w.end_array();
}

/// The plan of the pass tracked: the flip, the azimuth offset, whether it fits.
void write_track_plan(JsonWriter& w, const TrackStatus& t) {
  w.key("plan");
  if (!t.planned) {
    w.null();
    return;
  }
  w.begin_object()
      .member("flip", t.plan.flip)
      .member("az_offset_deg", t.plan.az_offset_deg)
      .member("fits", t.plan.fits)
      .member("unwinds", t.unwinds);
  write_utc(w, "preposition_utc", t.preposition_at_ms);
  w.end_object();
}

}  // namespace

void Api::write_track(JsonWriter& w) const {
  const Controller& c = ctx_.controller;
  const TrackStatus& t = c.track_status();
  w.begin_object().member("phase", track_phase_name(t.phase)).member("armed", t.armed());
  w.key("error");
  if (t.phase == TrackPhase::kFailed || t.error != TrackError::kOk) {
    w.string(track_error_text(t.error));
  } else {
    w.null();
  }
  if (t.sgp4_error != tracking::Sgp4Error::kOk)
    w.member("sgp4_error", tracking::sgp4_error_name(t.sgp4_error));
  w.key("target")
      .begin_object()
      .member("kind", kind_name(t.kind))
      .member("name", t.name)
      .member("catalog", t.catalog)
      .end_object();
  w.key("pass");
  if (t.have_pass) {
    write_pass(w, t.pass);
  } else {
    w.null();
  }
  write_track_plan(w, t);
  w.key("antenna_target");
  if (t.have_target) {
    w.begin_object().member("az", t.target_az_deg).member("el", t.target_el_deg).end_object();
  } else {
    w.null();
  }
  w.key("sky").begin_object().member("az", t.sky_az_deg).member("el", t.sky_el_deg).end_object();
  w.key("measured")
      .begin_object()
      .member("az_lag_ms", t.lag_ms[0])
      .member("el_lag_ms", t.lag_ms[1])
      .member("az_speed_deg_s", t.speed_deg_s[0])
      .member("el_speed_deg_s", t.speed_deg_s[1])
      .end_object();
  write_track_path(w, t, c.tracker().table());
  const std::optional<std::int64_t> utc = c.utc_ms();
  if (utc) {
    write_utc(w, "utc", *utc);
  } else {
    w.key("utc").null();
  }
  w.end_object();
}

}  // namespace rotord::web
