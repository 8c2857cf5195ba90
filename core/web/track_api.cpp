// The tracking endpoints of the REST API (docs/web_api.md#tracking): the
// stored TLEs, passes, and the tracking mode. Gating (who may call what) is
// in web_api.cpp's route table; each handler here checks its own methods.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "json/json_reader.hpp"
#include "tracking/julian.hpp"
#include "util/slice.hpp"
#include "web/query.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
namespace {

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

int track_error_status(TrackError e) {
  switch (e) {
    case TrackError::kNoClock:
    case TrackError::kClockUnsynced:
    case TrackError::kNoStation:
    case TrackError::kFaulted:
    case TrackError::kBelowHorizon:
      return 409;
    default:
      return 422;
  }
}

}  // namespace

void Api::handle_track(const HttpRequest& request, protocol::ByteSink& out,
                       const ResponseOptions& options) {
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
    if (m == Method::kPut) return put_tles(request, out, options);
    if (m == Method::kDelete) return delete_tle(request, out, options);
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
  if (m == Method::kPost) return post_track(request, out, options);
  if (m == Method::kDelete) {
    // Ends the track; the rotator stops where it is (as STOP).
    ctx_.controller.stop();
    send_json(out, 200, options, [this](JsonWriter& w) { write_track(w); });
    return;
  }
  refuse("Allow: GET, HEAD, POST, DELETE\r\n");
}

void Api::get_tles(protocol::ByteSink& out, const ResponseOptions& options) {
  if (ctx_.tles == nullptr) return send_error(out, 501, "this port keeps no TLEs", options);
  const std::optional<std::int64_t> utc = ctx_.controller.utc_ms();
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object().member("capacity", static_cast<int>(tracking::TleCatalog::kCapacity));
    w.key("objects").begin_array();
    for (std::size_t n = 0; n < ctx_.tles->size(); ++n) {
      const tracking::TleCatalog::Entry& e = ctx_.tles->entry(n);
      tracking::Tle tle;
      tracking::TleCatalog::elements(e, tle);
      const double epoch_ms = tracking::tle_epoch_unix_ms(tle.epoch_year, tle.epoch_day);
      w.begin_object().member("name", e.name).member("catalog", e.catalog);
      write_utc(w, "epoch_utc", static_cast<std::int64_t>(epoch_ms));
      w.key("age_days");
      if (utc) {
        w.number((static_cast<double>(*utc) - epoch_ms) / 86400000.0);
      } else {
        w.null();
      }
      w.member("line1", e.line1).member("line2", e.line2).end_object();
    }
    w.end_array().end_object();
  });
}

void Api::put_tles(const HttpRequest& request, protocol::ByteSink& out,
                   const ResponseOptions& options) {
  if (ctx_.tles == nullptr) return send_error(out, 501, "this port keeps no TLEs", options);
  const std::optional<std::int64_t> utc = ctx_.controller.utc_ms();
  const tracking::TleCheck check = ctx_.tles->put(request.body, utc.value_or(0));
  if (!check.ok()) {
    char message[160];
    check.describe(message, sizeof message);
    return send_error(out, check.problem == tracking::TleCheck::Problem::kFull ? 507 : 422, message,
                      options);
  }
  const bool saved = ctx_.tle_storage == nullptr ||
                     ctx_.tles->save(*ctx_.tle_storage, document_, sizeof document_);
  if (!saved)
    return send_error(out, 500, "the TLEs are stored in RAM but could not be saved", options);
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object()
        .member("ok", true)
        .member("added", static_cast<int>(check.added))
        .member("replaced", static_cast<int>(check.replaced))
        .member("count", static_cast<int>(ctx_.tles->size()))
        .member("saved", ctx_.tle_storage != nullptr)
        .end_object();
  });
}

void Api::delete_tle(const HttpRequest& request, protocol::ByteSink& out,
                     const ResponseOptions& options) {
  if (ctx_.tles == nullptr) return send_error(out, 501, "this port keeps no TLEs", options);
  char object[40];
  if (!query_value(request.query, "object", object, sizeof object))
    return send_error(out, 400, "name the object: DELETE /api/tle?object=NAME_OR_NUMBER", options);
  const tracking::TleCatalog::Entry* e = ctx_.tles->find(object);
  if (e == nullptr) return send_error(out, 404, "no such object stored", options);
  ctx_.tles->remove(e->catalog);
  if (ctx_.tle_storage != nullptr &&
      !ctx_.tles->save(*ctx_.tle_storage, document_, sizeof document_))
    return send_error(out, 500, "removed in RAM but could not be saved", options);
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object()
        .member("ok", true)
        .member("count", static_cast<int>(ctx_.tles->size()))
        .end_object();
  });
}

void Api::work_passes(int evaluations) {
  PassSearch& s = passes_;
  if (!s.active) return;
  while (evaluations > 0) {
    // The finder counts its evaluations; give it the rest in slices.
    const int slice = evaluations > 200 ? 200 : evaluations;
    evaluations -= slice;
    switch (s.finder.step(slice)) {
      case tracking::PassFinder::Status::kSearching:
        break;
      case tracking::PassFinder::Status::kFound:
        if (s.count < PassSearch::kMaxPasses) s.passes[s.count++] = s.finder.pass();
        if (s.count == PassSearch::kMaxPasses) s.active = false;
        break;
      case tracking::PassFinder::Status::kDone:
        s.active = false;
        break;
      case tracking::PassFinder::Status::kError:
        s.error = s.finder.error();
        s.active = false;
        break;
    }
    if (!s.active) return;
  }
}

void Api::get_passes(const HttpRequest& request, protocol::ByteSink& out,
                     const ResponseOptions& options) {
  char object[40] = {};
  if (!query_value(request.query, "object", object, sizeof object))
    return send_error(out, 400, "name the object: /api/passes?object=NAME_OR_NUMBER|sun|moon",
                      options);
  int hours = 24;
  char number[16];
  if (query_value(request.query, "hours", number, sizeof number)) {
    hours = std::atoi(number);
    if (hours < 1 || hours > 72) return send_error(out, 422, "hours must be 1..72", options);
  }
  double min_el = ctx_.controller.settings().get(settings::Id::kTrackMinElDeg);
  if (query_value(request.query, "min_el", number, sizeof number)) {
    char* end = nullptr;
    min_el = std::strtod(number, &end);
    if (end == number || *end != '\0' || min_el < 0 || min_el > 89)
      return send_error(out, 422, "min_el must be 0..89 (degrees)", options);
  }
  if (!ctx_.controller.station_set())
    return send_error(out, 409, track_error_text(TrackError::kNoStation), options);
  const std::optional<std::int64_t> utc = ctx_.controller.utc_ms();
  if (!utc) return send_error(out, 409, "the time (UTC) is not known yet", options);
  PassSearch& s = passes_;
  const bool same = s.valid && std::strcmp(s.key, object) == 0 && s.hours == hours &&
                    s.min_el_deg == min_el && *utc - s.from_ms < 60000 && *utc >= s.from_ms;
  if (!same) {
    // A new search. The target is looked up now; the search runs here and
    // in poll() a slice at a time.
    TargetKind kind = TargetKind::kSatellite;
    if (std::strcmp(object, "sun") == 0) {
      s.target.set_body(tracking::Body::kSun);
      kind = TargetKind::kSun;
    } else if (std::strcmp(object, "moon") == 0) {
      s.target.set_body(tracking::Body::kMoon);
      kind = TargetKind::kMoon;
    }
    if (kind == TargetKind::kSatellite) {
      const tracking::TleCatalog::Entry* e =
          ctx_.tles != nullptr ? ctx_.tles->find(object) : nullptr;
      if (e == nullptr)
        return send_error(out, 404, "no such object stored (PUT /api/tle)", options);
      tracking::Tle tle;
      tracking::TleCatalog::elements(*e, tle);
      if (s.target.set_satellite(tle) != tracking::Sgp4Error::kOk)
        return send_error(out, 422, "SGP4 cannot use this object's elements", options);
    }
    std::memcpy(s.key, object, sizeof s.key);
    s.hours = hours;
    s.min_el_deg = min_el;
    s.from_ms = *utc;
    s.count = 0;
    s.error = tracking::Sgp4Error::kOk;
    s.valid = true;
    s.active = true;
    s.finder.start(s.target, ctx_.controller.observer(), *utc,
                   *utc + static_cast<std::int64_t>(hours) * 3600000, min_el);
    work_passes(ctx_.passes_request_budget);
  }
  const int status = s.active ? 202 : (s.error != tracking::Sgp4Error::kOk ? 422 : 200);
  send_json(out, status, options, [&](JsonWriter& w) {
    w.begin_object()
        .member("object", s.key)
        .member("hours", s.hours)
        .member("min_el_deg", s.min_el_deg);
    write_utc(w, "from_utc", s.from_ms);
    w.member("complete", !s.active);
    if (s.error != tracking::Sgp4Error::kOk) w.member("error", tracking::sgp4_error_name(s.error));
    w.key("passes").begin_array();
    for (std::size_t n = 0; n < s.count; ++n) write_pass(w, s.passes[n]);
    w.end_array().end_object();
  });
}

void Api::post_track(const HttpRequest& request, protocol::ByteSink& out,
                     const ResponseOptions& options) {
  if (!request.json_body)
    return send_error(out, 415, "send Content-Type: application/json", options);
  JsonObjectReader reader(request.body.empty() ? std::string_view("{}") : request.body);
  if (!reader.valid()) {
    char message[120];
    std::snprintf(message, sizeof message, "invalid JSON: %s", reader.error());
    return send_error(out, 400, message, options);
  }
  char object[40] = {};
  char body[8] = {};
  char when[8] = {};
  bool have_az = false, have_el = false;
  double az = 0, el = 0;
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    char* text =
        key == "object" ? object : (key == "body" ? body : (key == "when" ? when : nullptr));
    const std::size_t cap =
        key == "object" ? sizeof object : (key == "body" ? sizeof body : sizeof when);
    if (text != nullptr) {
      if (value.type != JsonType::kString)
        return send_error(out, 400, "object, body and when are strings", options);
      if (value.truncated || value.text.size() >= cap)
        return send_error(out, 422, "object, body or when is too long", options);
      std::memcpy(text, value.text.data(), value.text.size());
      text[value.text.size()] = '\0';
    } else if (key == "az" || key == "el") {
      if (value.type != JsonType::kNumber)
        return send_error(out, 400, "az and el are numbers", options);
      (key == "az" ? have_az : have_el) = true;
      (key == "az" ? az : el) = value.number;
    } else {
      char message[96];
      std::snprintf(message, sizeof message, "unknown member '%.*s'",
                    static_cast<int>(key.size() > 40 ? 40 : key.size()), key.data());
      return send_error(out, 400, message, options);
    }
  }
  const int targets = (object[0] != '\0') + (body[0] != '\0') + (have_az || have_el);
  if (targets != 1)
    return send_error(out, 400, "give one of: object (a stored TLE), body (sun or moon), az/el",
                      options);
  TrackRequest r;
  if (when[0] == '\0' || std::strcmp(when, "next") == 0) {
    r.when = TrackWhen::kNextPass;
  } else if (std::strcmp(when, "now") == 0) {
    r.when = TrackWhen::kNow;
  } else {
    return send_error(out, 422, "when must be now or next", options);
  }
  if (object[0] != '\0') {
    const tracking::TleCatalog::Entry* e = ctx_.tles != nullptr ? ctx_.tles->find(object) : nullptr;
    if (e == nullptr) return send_error(out, 404, "no such object stored (PUT /api/tle)", options);
    r.kind = TargetKind::kSatellite;
    tracking::TleCatalog::elements(*e, r.tle);
  } else if (body[0] != '\0') {
    if (std::strcmp(body, "sun") != 0 && std::strcmp(body, "moon") != 0)
      return send_error(out, 422, "body must be sun or moon", options);
    r.kind = body[0] == 's' ? TargetKind::kSun : TargetKind::kMoon;
  } else {
    if (!have_az) return send_error(out, 400, "give az (and el) in degrees", options);
    r.kind = TargetKind::kNone;
    r.az_deg = static_cast<float>(az);
    r.el_deg = static_cast<float>(el);
  }
  const TrackError e = ctx_.controller.track(r);
  if (e != TrackError::kOk) {
    const TrackStatus& t = ctx_.controller.track_status();
    char message[384];
    if (t.sgp4_error != tracking::Sgp4Error::kOk) {
      std::snprintf(message, sizeof message, "%s (%s)", track_error_text(e),
                    tracking::sgp4_error_name(t.sgp4_error));
    } else {
      std::snprintf(message, sizeof message, "%s", track_error_text(e));
    }
    return send_error(out, track_error_status(e), message, options);
  }
  send_json(out, 200, options, [this](JsonWriter& w) { write_track(w); });
}

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
  w.key("plan");
  if (t.planned) {
    w.begin_object()
        .member("flip", t.plan.flip)
        .member("az_offset_deg", t.plan.az_offset_deg)
        .member("fits", t.plan.fits)
        .member("unwinds", t.unwinds);
    write_utc(w, "preposition_utc", t.preposition_at_ms);
    w.end_object();
  } else {
    w.null();
  }
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
  // The planned pass on the sky (for the Track page's polar plot): up to 60
  // points of azimuth and elevation.
  w.key("path").begin_array();
  const tracking::PassTable& table = c.tracker().table();
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
  const std::optional<std::int64_t> utc = c.utc_ms();
  if (utc) {
    write_utc(w, "utc", *utc);
  } else {
    w.key("utc").null();
  }
  w.end_object();
}

}  // namespace rotord::web
