#include "web/place_api.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "command/result.hpp"
#include "rotator/place.hpp"
#include "tracking/sun_moon.hpp"
#include "web/query.hpp"

namespace rotord::web {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

/// The place a query string names; nullptr, or why not.
const char* place_from_query(std::string_view query, PlaceQuery& q) {
  char locator[16], lat[24], lon[24], path[8];
  const char* why = nullptr;
  if (query_value(query, "locator", locator, sizeof locator)) {
    why = place_from_locator(locator, q);
  } else if (query_value(query, "lat", lat, sizeof lat) &&
             query_value(query, "lon", lon, sizeof lon)) {
    char* lat_end = nullptr;
    char* lon_end = nullptr;
    const double lat_deg = std::strtod(lat, &lat_end);
    const double lon_deg = std::strtod(lon, &lon_end);
    if (lat_end == lat || *lat_end != '\0' || lon_end == lon || *lon_end != '\0')
      return "lat and lon are numbers of degrees";
    why = place_from_lat_lon(lat_deg, lon_deg, q);
  } else {
    return "give locator=, or lat= and lon=";
  }
  if (why == nullptr && query_value(query, "path", path, sizeof path)) why = place_path(path, q);
  return why;
}

/// A body's sub-point (where it is overhead) and where the station sees it.
void write_body(JsonWriter& w, const tracking::Observer& o, tracking::Body body,
                std::int64_t unix_ms) {
  const tracking::EcefState e = tracking::body_ecef(body, unix_ms);
  const double* r = e.r_km;
  const tracking::LookAngles look = o.look(e);
  w.begin_object()
      .member("lat_deg", std::atan2(r[2], std::hypot(r[0], r[1])) * kRadToDeg)
      .member("lon_deg", std::atan2(r[1], r[0]) * kRadToDeg)
      .member("az_deg", look.az_deg)
      .member("el_deg", look.el_deg)
      .end_object();
}

}  // namespace

Api::Outcome get_place(Api& api, const Api::Call& call) {
  PlaceQuery q;
  if (const char* why = place_from_query(call.request.query, q)) {
    send_error(call.out, 400, why, call.options);
    return Api::Outcome::kDone;
  }
  const PlaceAim aim = aim_at(api.controller(), q);
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object();
    command::write_aim(w, q, aim);
    w.end_object();
  });
  return Api::Outcome::kDone;
}

Api::Outcome get_sky(Api& api, const Api::Call& call) {
  Controller& c = api.controller();
  const settings::Settings& s = c.settings();
  const std::optional<std::int64_t> utc = c.utc_ms();
  const tracking::Observer o = c.observer();
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object()
        .key("station")
        .begin_object()
        .member("lat_deg", s.get(settings::Id::kStationLatDeg))
        .member("lon_deg", s.get(settings::Id::kStationLonDeg))
        .end_object()
        .member("beamwidth_deg", s.get(settings::Id::kAzBeamwidthDeg));
    w.key("time_ms");
    if (utc) {
      w.integer(static_cast<long long>(*utc));
    } else {
      w.null();
    }
    w.key("sun");
    if (utc) {
      write_body(w, o, tracking::Body::kSun, *utc);
    } else {
      w.null();
    }
    w.key("moon");
    if (utc) {
      write_body(w, o, tracking::Body::kMoon, *utc);
    } else {
      w.null();
    }
    w.end_object();
  });
  return Api::Outcome::kDone;
}

void write_beam(JsonWriter& w, const RotatorStatus& s) {
  w.key("beam");
  if (!s.az.position_valid) {
    w.null();
    return;
  }
  const bool el = s.el.present && s.el.position_valid;
  const Beam b = beam_of(s.az.position_deg, el ? s.el.position_deg : 0.0, el);
  w.begin_object().member("az_deg", b.az_deg).key("el_deg");
  if (el) {
    w.number(b.el_deg);
  } else {
    w.null();
  }
  w.key("target_az_deg");
  if (s.az.has_target) {
    const Beam t = beam_of(s.az.target_deg,
                           el && s.el.has_target ? s.el.target_deg
                           : el                  ? s.el.position_deg
                                                 : 0.0,
                           el);
    w.number(t.az_deg);
  } else {
    w.null();
  }
  w.end_object();
}

}  // namespace rotord::web
