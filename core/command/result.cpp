#include "command/result.hpp"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace rotord::command {

int http_status(Status s) {
  switch (s) {
    case Status::kOk:
      return 200;
    case Status::kBadRequest:
      return 400;
    case Status::kForbidden:
      return 403;
    case Status::kNotFound:
      return 404;
    case Status::kConflict:
      return 409;
    case Status::kUnprocessable:
      return 422;
    case Status::kLocked:
      return 423;
    case Status::kUnavailable:
      return 503;
  }
  return 500;
}

std::string_view status_word(Status s) {
  static constexpr std::string_view kWords[] = {"OK",        "BAD REQUEST", "DENIED",
                                                "NOT FOUND", "CONFLICT",    "UNPROCESSABLE",
                                                "LOCKED",    "UNAVAILABLE"};
  return kWords[static_cast<std::size_t>(s)];
}

Result refused(Status status, std::string_view message) {
  Result r;
  r.status = status;
  const std::size_t n =
      message.size() < sizeof r.message - 1 ? message.size() : sizeof r.message - 1;
  if (n > 0) std::memcpy(r.message, message.data(), n);
  r.message[n] = '\0';
  return r;
}

Result refusedf(Status status, const char* format, ...) {
  Result r;
  r.status = status;
  va_list args;
  va_start(args, format);
  std::vsnprintf(r.message, sizeof r.message, format, args);
  va_end(args);
  return r;
}

Result refused_by(Error e) {
  switch (e) {
    case Error::kFaulted:
      return refused(Status::kConflict,
                     "an axis has a latched fault: clear it with POST /api/reset");
    case Error::kLimit:
      return refused(Status::kConflict, "that direction is blocked by a limit");
    case Error::kStowed:
      return refused(Status::kConflict,
                     "stowed for the wind: moves are refused until it is calm, or an operator "
                     "overrides the stow (POST /api/wind/override)");
    case Error::kNotSupported:
      return refused(Status::kUnprocessable, "this rotator has no elevation axis");
    case Error::kOutOfRange:
      return refused(Status::kUnprocessable, "outside the allowed range");
    default:
      return refused(Status::kUnprocessable, error_name(e));
  }
}

void write_aim(web::JsonWriter& w, const PlaceQuery& q, const PlaceAim& aim) {
  w.key("to").begin_object();
  if (q.locator[0] != '\0') w.member("locator", q.locator);
  w.member("lat_deg", q.to.lat_deg).member("lon_deg", q.to.lon_deg).end_object();
  w.member("path", q.path == tracking::Path::kLong ? "long" : "short")
      .member("bearing_deg", std::round(aim.bearing.azimuth_deg * 100.0) / 100.0)
      .member("distance_km", std::round(aim.bearing.distance_km * 10.0) / 10.0)
      .member("reachable", aim.reachable);
  if (!aim.reachable) w.member("why", aim.why);
}

void write_result(web::JsonWriter& w, const Result& r) {
  if (!r.ok()) {
    w.begin_object().member("error", std::string_view(r.message)).end_object();
    return;
  }
  w.begin_object().member("ok", true);
  switch (r.reply) {
    case Reply::kOk:
      break;
    case Reply::kGoto:
      w.key("az_target");
      if (r.has_az_target) {
        w.number(r.az_target_deg);
      } else {
        w.null();
      }
      w.key("el_target");
      if (r.has_el_target) {
        w.number(r.el_target_deg);
      } else {
        w.null();
      }
      break;
    case Reply::kPlace: {
      PlaceAim aim;  // a reply only when reachable: no why
      aim.bearing = r.bearing;
      aim.reachable = true;
      write_aim(w, r.place, aim);
      break;
    }
    case Reply::kPreset:
      w.member("name", std::string_view(r.preset_name)).member("az_deg", r.preset_az_deg);
      break;
  }
  w.end_object();
}

}  // namespace rotord::command
