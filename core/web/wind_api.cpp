#include "web/wind_api.hpp"

#include <cmath>

#include "command/care_commands.hpp"
#include "json/json_reader.hpp"
#include "web/http_response.hpp"

namespace rotord::web {
namespace {

using care::WindReject;
using care::WindState;

constexpr const char* kSources[] = {"off", "mqtt", "pulses"};

}  // namespace

void write_wind_status(JsonWriter& w, const Controller& c) {
  const care::WindStow& wind = c.wind();
  const Millis now = c.now();
  w.key("wind").begin_object();
  w.member("source", kSources[static_cast<std::size_t>(wind.config().source)])
      .member("state", care::wind_state_name(wind.state()));
  w.key("speed_mps");
  if (wind.has_speed()) {
    w.number(wind.speed_mps());
  } else {
    w.null();
  }
  w.key("dir_deg");
  if (wind.has_fresh_direction(now)) {
    w.number(wind.direction_deg());
  } else {
    w.null();
  }
  w.member("stow_mps", wind.config().stow_mps)
      .member("calm_mps", wind.config().calm_mps)
      .member("stow_az_deg", c.wind_stow_az_deg())
      .member("refusing", wind.refusing())
      .member("stopped_by_operator", wind.stopped())
      .member("calm_left_s", static_cast<long long>(wind.calm_left_ms(now) / 1000))
      .member("override_left_s", static_cast<long long>(wind.override_left_ms(now) / 1000))
      .member("stows", wind.stows())
      .member("overrides", wind.overrides())
      .member("readings", wind.readings());
  w.key("rejected").begin_object();
  for (std::size_t n = 0; n < care::kWindRejectKinds; ++n) {
    const auto why = static_cast<WindReject>(n);
    w.member(care::wind_reject_name(why), wind.rejected(why));
  }
  w.end_object().end_object();
}

Api::Outcome post_wind_override(Api& api, const Api::Call& call) {
  long long minutes = 0;
  bool end = false;
  const std::string_view body = call.request.body;
  if (!body.empty()) {
    JsonObjectReader reader(body);
    std::string_view key;
    JsonValue value;
    const char* why = nullptr;
    while (why == nullptr && reader.valid() && reader.next(key, value)) {
      if (key == "minutes" && value.type == JsonType::kNumber && std::isfinite(value.number) &&
          value.number == std::floor(value.number) && value.number >= 0 && value.number <= 1440) {
        minutes = static_cast<long long>(value.number);
      } else if (key == "end" && value.type == JsonType::kBool) {
        end = value.boolean;
      } else {
        why = "the body is {\"minutes\": 0..1440} (0: wind.override_min) or {\"end\": true}";
      }
    }
    if (why == nullptr && !reader.valid()) why = "invalid JSON";
    if (why != nullptr) {
      send_error(call.out, 400, why, call.options);
      return Api::Outcome::kDone;
    }
  }
  Controller& c = api.controller();
  const command::Origin from{"rest", call.peer};
  if (end) {
    if (command::end_wind_override(c, from) != Error::kOk) {
      send_error(call.out, 409, "no override of a wind stow is running", call.options);
      return Api::Outcome::kDone;
    }
  } else if (command::wind_override(c, from, static_cast<int>(minutes)) != Error::kOk) {
    send_error(call.out, 409, "nothing to override: the antenna is not stowed for the wind",
               call.options);
    return Api::Outcome::kDone;
  }
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object().member("ok", true);
    write_wind_status(w, c);
    w.end_object();
  });
  return Api::Outcome::kDone;
}

void write_wind_metrics(metrics::PrometheusWriter& w, const Controller& c) {
  const care::WindStow& wind = c.wind();
  w.family("rotord_wind_speed_mps", "gauge",
           "The last wind speed read (wind.source), m/s; absent until a reading came.");
  if (wind.has_speed()) w.value({}, static_cast<double>(wind.speed_mps()));
  w.family("rotord_wind_stowed", "gauge",
           "1 while stowed for the wind and refusing other moves (not during an override).");
  w.integer({}, wind.refusing() ? 1 : 0);
  w.family("rotord_wind_override", "gauge", "1 while an operator overrides a wind stow.");
  w.integer({}, wind.state() == WindState::kOverride ? 1 : 0);
  w.family("rotord_wind_stows_total", "counter", "Wind stows begun since start.");
  w.integer({}, wind.stows());
  w.family("rotord_wind_overrides_total", "counter", "Operator overrides of a wind stow.");
  w.integer({}, wind.overrides());
  w.family("rotord_wind_readings_total", "counter", "Wind speed readings taken.");
  w.integer({}, wind.readings());
  w.family("rotord_wind_readings_rejected_total", "counter",
           "Wind readings ignored, by reason (garbage, negative, too_high, bad_direction, "
           "stale).");
  for (std::size_t n = 0; n < care::kWindRejectKinds; ++n) {
    const auto why = static_cast<WindReject>(n);
    w.integer({{"reason", care::wind_reject_name(why)}}, wind.rejected(why));
  }
}

}  // namespace rotord::web
