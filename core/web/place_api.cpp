#include "web/place_api.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "json/json_reader.hpp"
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

/// The place a POST body names; nullptr, or why not.
const char* place_from_body(std::string_view body, PlaceQuery& q, char* why_buf, std::size_t cap) {
  JsonObjectReader reader(body);
  if (!reader.valid()) return "invalid JSON";
  std::string_view key;
  JsonValue value;
  bool has_locator = false, has_lat = false, has_lon = false;
  double lat = 0, lon = 0;
  char path[8] = "short";
  while (reader.next(key, value)) {
    const bool number = value.type == JsonType::kNumber;
    const bool text = value.type == JsonType::kString;
    if (key == "locator" && text) {
      if (const char* why = place_from_locator(value.text, q)) return why;
      has_locator = true;
    } else if (key == "lat" && number) {
      lat = value.number;
      has_lat = true;
    } else if (key == "lon" && number) {
      lon = value.number;
      has_lon = true;
    } else if (key == "path" && text) {
      // A word longer than "short" is no path: kept as "?" to be refused.
      const std::size_t n = value.text.size() < sizeof path ? value.text.size() : 0;
      if (n > 0) std::memcpy(path, value.text.data(), n);
      path[n] = n == 0 ? '?' : '\0';
      path[n == 0 ? 1 : n] = '\0';
    } else {
      std::snprintf(why_buf, cap, "'%.*s' is not a member here (locator, lat, lon, path)",
                    static_cast<int>(key.size() > 24 ? 24 : key.size()), key.data());
      return why_buf;
    }
  }
  if (!reader.valid()) return "invalid JSON";
  if (has_locator == (has_lat || has_lon)) return "give locator, or lat and lon";
  if (!has_locator) {
    if (!has_lat || !has_lon) return "give both lat and lon";
    if (const char* why = place_from_lat_lon(lat, lon, q)) return why;
  }
  return place_path(path, q);
}

void write_aim(JsonWriter& w, const PlaceQuery& q, const PlaceAim& aim) {
  w.key("to").begin_object();
  if (q.locator[0] != '\0') w.member("locator", q.locator);
  w.member("lat_deg", q.to.lat_deg).member("lon_deg", q.to.lon_deg).end_object();
  w.member("path", q.path == tracking::Path::kLong ? "long" : "short")
      .member("bearing_deg", std::round(aim.bearing.azimuth_deg * 100.0) / 100.0)
      .member("distance_km", std::round(aim.bearing.distance_km * 10.0) / 10.0)
      .member("reachable", aim.reachable);
  if (!aim.reachable) w.member("why", aim.why);
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
    write_aim(w, q, aim);
    w.end_object();
  });
  return Api::Outcome::kDone;
}

Api::Outcome post_place(Api& api, const Api::Call& call) {
  PlaceQuery q;
  char why_buf[80];
  if (const char* why = place_from_body(call.request.body, q, why_buf, sizeof why_buf)) {
    send_error(call.out, 400, why, call.options);
    return Api::Outcome::kDone;
  }
  const PlaceAim aim = aim_at(api.controller(), q);
  if (!aim.reachable) {
    send_error(call.out, 422, aim.why, call.options);
    return Api::Outcome::kDone;
  }
  const Error e = turn_to(api.controller(), aim);
  if (e != Error::kOk) {
    send_error(call.out, e == Error::kFaulted ? 409 : 422,
               e == Error::kFaulted ? "an axis has a latched fault: clear it with POST /api/reset"
                                    : error_name(e),
               call.options);
    return Api::Outcome::kDone;
  }
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object().member("ok", true);
    write_aim(w, q, aim);
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
