#include "web/recognition_report.hpp"

#include <cstdio>

#include "util/utc_time.hpp"

namespace rotord::web {
namespace {

const char* kind_name(tracking::TargetKind kind) {
  switch (kind) {
    case tracking::TargetKind::kSatellite:
      return "satellite";
    case tracking::TargetKind::kSun:
      return "sun";
    case tracking::TargetKind::kMoon:
      return "moon";
    case tracking::TargetKind::kNone:
      break;
  }
  return "none";
}

void utc_member(JsonWriter& w, const char* name, std::int64_t unix_ms) {
  w.key(name);
  char utc[32];
  const std::size_t n = unix_ms > 0 ? format_utc_iso8601(unix_ms, utc, sizeof utc) : 0;
  if (n > 0) {
    w.string(std::string_view(utc, n));
  } else {
    w.null();
  }
}

}  // namespace

void write_recognition(JsonWriter& w, const Recognition& r) {
  w.key("recognised");
  if (r.begun == 0) {
    w.null();
    return;
  }
  w.begin_object()
      .member("active", r.active)
      .member("object", r.name)
      .member("kind", kind_name(r.kind))
      .member("catalog", static_cast<long long>(r.catalog))
      .member("gotos", static_cast<long long>(r.gotos))
      .member("count", static_cast<long long>(r.begun));
  utc_member(w, "since_utc", r.began_utc_ms);
  if (r.active) {
    w.key("ended").null();
    w.key("ended_utc").null();
  } else {
    w.member("ended", recognition_end_name(r.ended));
    utc_member(w, "ended_utc", r.ended_utc_ms);
  }
  w.end_object();
}

void write_recognition_metrics(metrics::PrometheusWriter& w, const Recognition& r) {
  w.family("rotord_goto_recognised_total", "counter",
           "Passes of a stored satellite, the Sun or the Moon recognised in a client's go-to "
           "stream and followed (track.recognise).");
  w.integer({}, r.begun);
  w.family("rotord_goto_recognised", "gauge",
           "1 while rotord follows the pass of the object it recognised in a client's go-to "
           "stream (labelled object and catalog), else 0.");
  if (r.active) {
    char catalog[12];
    std::snprintf(catalog, sizeof catalog, "%u", static_cast<unsigned>(r.catalog));
    w.integer({{"object", r.name}, {"catalog", catalog}}, 1);
  } else {
    w.integer({}, 0);
  }
}

}  // namespace rotord::web
