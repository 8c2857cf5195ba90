// GET /api/passes (docs/web_api.md#tracking): the next passes of a stored
// object, the Sun or the Moon, searched a slice at a time (the Pico W's
// loop must not stall).
#include <cstdlib>
#include <cstring>

#include "web/query.hpp"
#include "web/track_json.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

using tracking::TargetKind;

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

bool Api::start_pass_search(const char* object, int hours, double min_el, std::int64_t utc_ms,
                            protocol::ByteSink& out, const ResponseOptions& options) {
  PassSearch& s = passes_;
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
    const tracking::TleCatalog::Entry* e = ctx_.tles != nullptr ? ctx_.tles->find(object) : nullptr;
    if (e == nullptr) {
      send_error(out, 404, "no such object stored (PUT /api/tle)", options);
      return false;
    }
    tracking::Tle tle;
    tracking::TleCatalog::elements(*e, tle);
    if (s.target.set_satellite(tle) != tracking::Sgp4Error::kOk) {
      send_error(out, 422, "SGP4 cannot use this object's elements", options);
      return false;
    }
  }
  std::memcpy(s.key, object, sizeof s.key);
  s.hours = hours;
  s.min_el_deg = min_el;
  s.from_ms = utc_ms;
  s.count = 0;
  s.error = tracking::Sgp4Error::kOk;
  s.valid = true;
  s.active = true;
  s.finder.start(s.target, ctx_.controller.observer(), utc_ms,
                 utc_ms + static_cast<std::int64_t>(hours) * 3600000, min_el);
  work_passes(ctx_.passes_request_budget);
  return true;
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
  if (!same && !start_pass_search(object, hours, min_el, *utc, out, options)) return;
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

}  // namespace rotord::web
