#include "mqtt/bridge.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>

#include "command/commands.hpp"
#include "json/json_writer.hpp"
#include "mqtt/fixed_sink.hpp"
#include "util/slice.hpp"

namespace rotord::mqtt {
namespace {

using settings::Id;

int tenths(float deg) {
  return std::isfinite(deg) ? static_cast<int>(std::lround(deg * 10.0f)) : 0;
}

std::size_t copy_text(std::string_view from, char* out, std::size_t cap) {
  const std::size_t n = from.size() < cap - 1 ? from.size() : cap - 1;
  if (n > 0) std::memcpy(out, from.data(), n);  // an empty view's data() may be null
  out[n] = '\0';
  return n;
}

// Home Assistant's entities of the rotator itself, announced in this order
// (announce's steps 0..kEntityCount-1).
enum class Kind : unsigned char {
  kSensorAz,
  kSensorEl,
  kNumberAz,
  kStop,
  kPark,
  kFault,
  kSensorMechAz
};
struct Entity {
  Kind kind;
  const char* component;
  const char* object;
  const char* name;
};
constexpr Entity kEntities[] = {
    {Kind::kSensorAz, "sensor", "azimuth", "Azimuth"},
    {Kind::kSensorEl, "sensor", "elevation", "Elevation"},
    {Kind::kNumberAz, "number", "target_azimuth", "Target azimuth"},
    {Kind::kStop, "button", "stop", "Stop"},
    {Kind::kPark, "button", "park", "Park"},
    {Kind::kFault, "binary_sensor", "fault", "Fault"},
    {Kind::kSensorMechAz, "sensor", "mechanical_azimuth", "Mechanical azimuth"},
};

}  // namespace

Bridge::Bridge(web::Api& api, Transport& transport, std::string_view prefix,
               std::string_view node_id, std::string_view device_name)
    : api_(&api), transport_(transport) {
  prefix_len_ = copy_text(prefix, prefix_, sizeof prefix_);
  copy_text(node_id, node_id_, sizeof node_id_);
  copy_text(device_name, device_name_, sizeof device_name_);
  availability_len_ =
      join_topic(this->prefix(), "availability", availability_, sizeof availability_);
  command_filter_len_ =
      join_topic(this->prefix(), "cmd/+", command_filter_, sizeof command_filter_);
  // Subscribed whenever set, so that wind.source may change without a
  // restart; the controller takes the readings only from its source.
  const settings::Settings& s = api.settings();
  copy_text(s.text(Id::kWindMqttTopic), wind_topic_, sizeof wind_topic_);
  copy_text(s.text(Id::kWindMqttDirTopic), wind_dir_topic_, sizeof wind_dir_topic_);
}

Bridge::Fingerprint Bridge::fingerprint() const {
  const Controller& c = api_->controller();
  const RotatorStatus s = c.status();
  Fingerprint f;
  f.mode = static_cast<int>(s.mode);
  f.wind_state = static_cast<int>(s.wind_state);
  f.speed_pct = s.speed_pct;
  f.fault = s.any_fault();
  f.lock = api_->controller().control_lock().held();
  f.az_valid = s.az.position_valid;
  f.az_target = s.az.has_target;
  f.az_target_tenths = s.az.has_target ? tenths(s.az.target_deg) : 0;
  f.az_state = static_cast<int>(s.az.state);
  f.az_fault = static_cast<int>(s.az.fault);
  if (s.el.present) {
    f.el_valid = s.el.position_valid;
    f.el_target = s.el.has_target;
    f.el_target_tenths = s.el.has_target ? tenths(s.el.target_deg) : 0;
    f.el_state = static_cast<int>(s.el.state);
    f.el_fault = static_cast<int>(s.el.fault);
  }
  return f;
}

bool Bridge::position_changed() const {
  const RotatorStatus s = api_->controller().status();
  if (std::fabs(s.az.position_deg - last_az_deg_) >= kPositionStepDeg) return true;
  return s.el.present && std::fabs(s.el.position_deg - last_el_deg_) >= kPositionStepDeg;
}

void Bridge::poll(Millis now_ms) {
  const bool connected = transport_.connected();
  if (!connected) {
    was_connected_ = false;
    return;
  }
  if (!was_connected_) {
    // A (re)connection: the broker may have lost everything retained.
    was_connected_ = true;
    announce_step_ = 0;
    have_published_ = false;
  }
  // In order, each once; a refused one waits for a later pass (the Pico's
  // lwIP client has room for a few messages at a time).
  if (presets_changed()) announce_step_ = 0;  // new preset buttons for Home Assistant
  while (announce_step_ < kAnnouncements) {
    if (!announce(announce_step_)) return;
    ++announce_step_;
  }
  const Fingerprint f = fingerprint();
  const bool changed = !have_published_ || !(f == last_) || position_changed();
  const int hz = api_->settings().i(Id::kMqttStateHz);
  const Millis period_ms = 1000 / (hz < 1 ? 1 : hz);
  const Millis since_ms = now_ms - last_publish_ms_;
  const bool moving = api_->controller().status().moving();
  bool due = false;
  if (!have_published_) {
    due = true;
  } else if (changed) {
    due = since_ms >= kMinStateGapMs;
  } else if (moving) {
    due = since_ms >= period_ms;
  }
  if (!due) return;
  if (publish_state()) {
    last_ = f;
    const RotatorStatus s = api_->controller().status();
    last_az_deg_ = s.az.position_deg;
    last_el_deg_ = s.el.present ? s.el.position_deg : 0.0f;
    have_published_ = true;
    last_publish_ms_ = now_ms;
  }
}

bool Bridge::publish_state() {
  FixedSink sink(state_, sizeof state_);
  {
    web::JsonWriter w(sink);
    api_->write_status(w);
  }
  if (sink.overflowed()) return false;
  const std::size_t n = join_topic(prefix(), "state", topic_, sizeof topic_);
  if (n == 0) return false;
  if (!transport_.publish(std::string_view(topic_, n), sink.view(), true)) return false;
  ++states_published_;
  return true;
}

void Bridge::on_message(std::string_view topic, std::string_view payload, bool oversized) {
  // The wind stow's topics first (a weather station's, outside our prefix).
  if (is_wind_topic(topic)) {
    Controller& c = api_->controller();
    const bool speed = topic == wind_topic();
    // An oversized payload is read as an empty one: counted as garbage.
    const std::string_view body = oversized ? std::string_view{} : payload;
    if (speed) {
      c.wind_speed_message(body);
    } else {
      c.wind_direction_message(body);
    }
    return;
  }
  const std::string_view name = command_name(prefix(), topic);
  if (name.empty()) {
    // Another rotord's (or our own) state, availability or info.
    if (station_ != nullptr && !oversized) station_->on_message(topic, payload);
    return;
  }
  ++commands_handled_;
  char name_copy[16];
  const std::string_view cmd(name_copy,
                             copy_text(text::slice(name, 0, 15), name_copy, sizeof name_copy));
  // The command layer's table: the REST API's POST endpoints of the same
  // names, with the same arguments, checks and errors.
  const command::Def* def = command::Commands::find(name);
  if (def == nullptr) {
    publish_result(
        cmd, 404,
        R"({"error":"unknown command: use goto, move, stop, park, reset, speed, place or preset"})");
    return;
  }
  command::Commands& commands = api_->commands();
  const bool stop = def->id == command::Id::kStop;
  if (oversized || payload.size() > kMaxCommandBytes) {
    // STOP needs no body: it is obeyed even when the body is refused.
    if (stop) commands.execute(command::Id::kStop, {{}, broker_peer_, {}, "mqtt"});
    publish_result(cmd, 413, R"j({"error":"command body too large (512 bytes at most)"})j");
    return;
  }
  // The command layer decides what the broker may do (mqtt.control, its
  // address in access.control_networks, the control lock).
  const command::Result r = commands.from_broker(def->id, broker_peer_, payload);
  FixedSink sink(state_, sizeof state_);  // free between state publishes
  {
    web::JsonWriter w(sink);
    command::write_result(w, r);
  }
  // state_ holds the body until publish_result copies it into message_.
  publish_result(cmd, sink.overflowed() ? 500 : command::http_status(r.status),
                 sink.overflowed() ? std::string_view(R"({"error":"no response"})") : sink.view());
}

void Bridge::publish_result(std::string_view command, int status, std::string_view body) {
  // {"cmd":..,"status":..,"response":<the REST API's JSON body>}
  char head[64];
  const int head_len = std::snprintf(head, sizeof head, R"({"cmd":"%.*s","status":%d,"response":)",
                                     static_cast<int>(command.size()), command.data(), status);
  if (head_len <= 0 || static_cast<std::size_t>(head_len) + body.size() + 1 > sizeof message_)
    return;
  std::memcpy(message_, head, static_cast<std::size_t>(head_len));
  if (!body.empty()) std::memcpy(message_ + head_len, body.data(), body.size());
  const std::size_t len = static_cast<std::size_t>(head_len) + body.size();
  message_[len] = '}';
  const std::size_t n = join_topic(prefix(), "result", topic_, sizeof topic_);
  if (n == 0) return;
  transport_.publish(std::string_view(topic_, n), std::string_view(message_, len + 1), false);
}

void Bridge::set_web_url(std::string_view url) {
  copy_text(url, web_url_, sizeof web_url_);
}

bool Bridge::announce(int step) {
  constexpr int kCareFirst = kEntityCount + static_cast<int>(settings::kPresetCount);
  if (step >= kCareFirst && step < kCareFirst + kCareSensorCount)
    return !api_->settings().b(Id::kMqttDiscovery) || publish_care_sensor(step - kCareFirst);
  if (step >= kEntityCount && step < kEntityCount + static_cast<int>(settings::kPresetCount))
    return !api_->settings().b(Id::kMqttDiscovery) || publish_preset_button(step - kEntityCount);
  if (step < kEntityCount)
    return !api_->settings().b(Id::kMqttDiscovery) || publish_discovery(step);
  return publish_info();
}

bool Bridge::publish_info() {
  FixedSink sink(message_, sizeof message_);
  {
    web::JsonWriter w(sink);
    w.begin_object()
        .member("rotord", version_)
        .member("name", device_name_)
        .member("web", web_url_)
        .end_object();
  }
  const std::size_t n = join_topic(prefix(), "info", topic_, sizeof topic_);
  if (n == 0 || sink.overflowed()) return true;  // cannot ever fit: not retried
  return transport_.publish(std::string_view(topic_, n), sink.view(), true);
}

bool Bridge::publish_discovery(int entity) {
  static_assert(std::size(kEntities) == kEntityCount, "one announcement per entity");
  if (entity < 0 || static_cast<std::size_t>(entity) >= std::size(kEntities)) return true;
  const Entity& e = kEntities[entity];
  // homeassistant/<component>/<node_id>/<object_id>/config
  char topic[kMaxTopicBytes];
  const int tn = std::snprintf(topic, sizeof topic, "homeassistant/%s/%s/%s/config", e.component,
                               node_id_, e.object);
  if (tn <= 0 || static_cast<std::size_t>(tn) >= sizeof topic) return true;
  const std::string_view config_topic(topic, static_cast<std::size_t>(tn));
  if (e.kind == Kind::kSensorEl && !api_->settings().b(Id::kElEnabled)) {
    // An empty retained config removes an entity published before.
    return transport_.publish(config_topic, {}, true);
  }
  char unique_id[72];
  std::snprintf(unique_id, sizeof unique_id, "%s_%s", node_id_, e.object);
  FixedSink sink(message_, sizeof message_);
  {
    web::JsonWriter w(sink);
    write_entity_head(w, e.name, unique_id);
    write_entity_body(w, entity);
    w.end_object();
  }
  if (sink.overflowed()) return true;  // cannot ever fit: not retried
  return transport_.publish(config_topic, sink.view(), true);
}

void Bridge::write_entity_body(web::JsonWriter& w, int entity) const {
  const Kind kind = kEntities[entity].kind;
  char state_topic[kMaxTopicBytes];
  join_topic(prefix(), "state", state_topic, sizeof state_topic);
  char command_topic[kMaxTopicBytes];
  switch (kind) {
    case Kind::kSensorAz:
    case Kind::kSensorEl:
    case Kind::kSensorMechAz:
      // Where the beam points (after a flip over the zenith); the
      // mechanism's azimuth beside it.
      w.member("state_topic", state_topic)
          .member("value_template",
                  kind == Kind::kSensorAz   ? "{{ value_json.beam.az_deg | round(1) }}"
                  : kind == Kind::kSensorEl ? "{{ value_json.beam.el_deg | round(1) }}"
                                            : "{{ value_json.az.position_deg | round(1) }}")
          .member("unit_of_measurement", "\xc2\xb0")
          .member("state_class", "measurement")
          .member("icon", "mdi:compass");
      break;
    case Kind::kNumberAz:
      join_topic(prefix(), "cmd/goto", command_topic, sizeof command_topic);
      w.member("command_topic", command_topic)
          .member("command_template", "{\"az\": {{ value }}}")
          .member("state_topic", state_topic)
          .member("value_template",
                  "{{ value_json.az.target_deg if value_json.az.target_deg is not none "
                  "else value_json.az.position_deg }}")
          .member("min", api_->settings().get(Id::kAzMinDeg))
          .member("max", api_->settings().get(Id::kAzMaxDeg))
          .member("step", 1)
          .member("mode", "box")
          .member("unit_of_measurement", "\xc2\xb0");
      break;
    case Kind::kStop:
    case Kind::kPark:
      join_topic(prefix(), kind == Kind::kStop ? "cmd/stop" : "cmd/park", command_topic,
                 sizeof command_topic);
      w.member("command_topic", command_topic).member("payload_press", "{}");
      break;
    case Kind::kFault:
      w.member("state_topic", state_topic)
          .member("value_template", "{{ 'ON' if value_json.fault else 'OFF' }}")
          .member("device_class", "problem");
      break;
  }
}

}  // namespace rotord::mqtt
