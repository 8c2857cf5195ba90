// The live state over REST: GET /api/status (and each event of
// /api/events, and the MQTT state), the MQTT station, the settings schema.
#include <cstdio>

#include "axis/sensor_registry.hpp"
#include "util/utc_time.hpp"
#include "web/care_api.hpp"
#include "web/place_api.hpp"
#include "web/recognition_report.hpp"
#include "web/web_api.hpp"
#include "web/wind_api.hpp"

namespace rotord::web {
namespace {

using settings::Id;

const char* dir_name(Direction d) {
  return d == Direction::kCw ? "cw" : d == Direction::kCcw ? "ccw" : "none";
}

const char* lower_name(const char* upper, char* buf, std::size_t cap) {
  std::size_t n = 0;
  for (; upper[n] != '\0' && n + 1 < cap; ++n)
    buf[n] = (upper[n] >= 'A' && upper[n] <= 'Z') ? static_cast<char>(upper[n] + 32) : upper[n];
  buf[n] = '\0';
  return buf;
}

void number_or_null(JsonWriter& w, const char* key, bool known, double value) {
  w.key(key);
  if (known) {
    w.number(value);
  } else {
    w.null();
  }
}

/// The fields a reading may lack: the pot's wiper voltage and what raw spans
/// (for the calibration page), the magnetometer's field, the target.
void write_optional_fields(JsonWriter& w, const AxisStatus& a) {
  const bool volts_known = a.raw_full_scale > 0.0f && a.adc_ref_v > 0.0f;
  number_or_null(w, "raw_volts", volts_known,
                 volts_known ? static_cast<double>(a.raw) * a.adc_ref_v / a.raw_full_scale : 0.0);
  number_or_null(w, "raw_full_scale", a.raw_full_scale > 0.0f, a.raw_full_scale);
  w.key("mag");
  if (a.mag_valid) {
    w.begin_object()
        .member("x", static_cast<int>(a.mag_x))
        .member("y", static_cast<int>(a.mag_y))
        .member("z", static_cast<int>(a.mag_z))
        .end_object();
  } else {
    w.null();
  }
  number_or_null(w, "target_deg", a.has_target, a.target_deg);
}

/// `sensor` is the stored *.sensor value: its row names it and its unit.
void write_axis(JsonWriter& w, const AxisStatus& a, int sensor) {
  const SensorInfo* row = find_sensor(sensor);
  if (row == nullptr) row = &sensor_info(SensorType::kPot);
  char name[24];
  w.begin_object()
      .member("position_deg", a.position_deg)
      .member("valid", a.position_valid)
      .member("speed_deg_s", a.speed_deg_s)
      .member("sensor", row->key)
      .member("raw", a.raw)
      .member("raw_unit", row->raw_unit);
  write_optional_fields(w, a);
  w.member("jogging", a.jogging)
      .member("arrived", a.arrived)
      .member("state", lower_name(axis_state_name(a.state), name, sizeof(name)))
      .member("dir", dir_name(a.drive_dir))
      .member("fault", lower_name(axis_fault_name(a.fault), name, sizeof(name)))
      .member("limit_cw", a.limit_cw)
      .member("limit_ccw", a.limit_ccw)
      .member("switch_cw", a.switch_cw)
      .member("switch_ccw", a.switch_ccw)
      .member("coast_s", a.coast_s)
      .member("moves", a.moves)
      .member("readings_rejected", a.readings_rejected)
      .member("slips", a.slips)
      .member("slipping", a.slipping)
      .member("reholds", a.reholds)
      .member("reholding", a.reholding)
      .member("reholds_refused", a.reholds_refused);
  w.key("outputs").begin_object();
  for (std::size_t n = 0; n < kOutputChannelCount; ++n)
    w.member(kOutputChannelNames[n], a.outputs.value[n]);
  w.end_object().end_object();
}

/// What reading the stored settings dropped: only when something is wrong,
/// so a status every 100 ms stays short.
void write_settings_load(JsonWriter& w, const settings::Settings& values, const LoadReport* load) {
  if (!values.access_unreadable() && (load == nullptr || load->empty())) return;
  w.key("settings_load").begin_object();
  w.member("access_unreadable", values.access_unreadable());
  w.key("dropped").begin_array();
  for (std::size_t n = 0; load != nullptr && n < load->size(); ++n)
    w.begin_object().member("key", (*load)[n].key).member("reason", (*load)[n].reason).end_object();
  w.end_array();
  w.member("more", static_cast<long long>(load != nullptr ? load->more() : 0));
  w.end_object();
}

void write_limits(JsonWriter& w, const Limits& l) {
  w.key("limits")
      .begin_object()
      .member("az_min", l.az_min_deg)
      .member("az_max", l.az_max_deg)
      .member("az_continuous", l.az_continuous)
      .member("has_el", l.has_el)
      .member("el_min", l.el_min_deg)
      .member("el_max", l.el_max_deg)
      .end_object();
}

}  // namespace

void Api::write_status(JsonWriter& w) const {
  const Controller& c = ctx_.controller;
  const RotatorStatus s = c.status();
  Controller& mutable_c = ctx_.controller;  // settings() is not const
  const settings::Settings& values = mutable_c.settings();
  w.begin_object()
      .member("version", ctx_.version)
      .member("time_ms", static_cast<long long>(c.now()));
  // Calendar time for the user (SNTP on the Pico W, the system clock on
  // Linux); null until known. The control tick never uses it.
  w.key("time_utc");
  char utc[32];
  const std::optional<std::int64_t> unix_ms =
      ctx_.wall_clock != nullptr ? ctx_.wall_clock->unix_ms() : std::nullopt;
  const std::size_t utc_len = unix_ms ? format_utc_iso8601(*unix_ms, utc, sizeof utc) : 0;
  if (utc_len > 0) {
    w.string(std::string_view(utc, utc_len));
  } else {
    w.null();
  }
  w.member("mode", mode_name(s.mode))
      .member("speed_pct", s.speed_pct)
      .member("speed_applies", ctx_.controller.speed_applies())
      .member("moving", s.moving())
      .member("fault", s.any_fault());
  write_limits(w, s.limits);
  w.key("park")
      .begin_object()
      .member("az", values.get(Id::kParkAzDeg))
      .member("el", values.get(Id::kParkElDeg))
      .end_object();
  w.key("lock");
  write_lock(w, nullptr);
  write_beam(w, s);
  write_recognition(w, c.recognition());
  write_odometer_status(w, ctx_.controller);
  write_wind_status(w, ctx_.controller);
  write_settings_load(w, values, ctx_.load_report);
  w.key("az");
  write_axis(w, s.az, values.i(Id::kAzSensor));
  w.key("el");
  if (s.el.present) {
    write_axis(w, s.el, values.i(Id::kElSensor));
  } else {
    w.null();
  }
  w.end_object();
}

Api::Outcome Api::get_status(const Call& call) {
  send_json(call.out, 200, call.options, [this](JsonWriter& w) { write_status(w); });
  return Outcome::kDone;
}

Api::Outcome Api::get_station(const Call& call) {
  if (station_ == nullptr) {
    // 200, not 404: the station page asks for this, and a page that meets a
    // 404 shows an error in the browser's console for a setting left off.
    send_json(call.out, 200, call.options, [](JsonWriter& w) {
      w.begin_object()
          .member("available", false)
          .member("reason",
                  "no station here: MQTT is off (mqtt.enabled), or this is a Pico W (a Linux "
                  "rotord on the same broker shows the station)")
          .key("rotators")
          .begin_array()
          .end_array()
          .end_object();
    });
  } else {
    send_json(call.out, 200, call.options, [this](JsonWriter& w) { station_->write_station(w); });
  }
  return Outcome::kDone;
}

Api::Outcome Api::get_events(const Call& call) {
  if (call.request.method == Method::kHead) {
    write_head(call.out, 200, "text/event-stream", -1, {false, true, {}});
    return Outcome::kClose;
  }
  // The stream ends when the connection closes: no length, no keep-alive.
  write_head(call.out, 200, "text/event-stream", -1, {false, false, "Cache-Control: no-store\r\n"});
  return Outcome::kStartEvents;
}

Api::Outcome Api::get_schema(const Call& call) {
  send_json(call.out, 200, call.options, [this](JsonWriter& w) {
    write_settings_schema(ctx_.defaults != nullptr ? *ctx_.defaults : settings::Settings(), w,
                          settings::platform_name(ctx_.platform));
  });
  return Outcome::kDone;
}

}  // namespace rotord::web
