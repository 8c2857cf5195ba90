// Home Assistant sensors for the wear odometer and the slips (issue 27,
// docs/care.md): read from the state topic (GET /api/status's "odometer"
// and each axis's "slips"), so they cost no topic of their own.
#include <cstdio>

#include "json/json_writer.hpp"
#include "mqtt/bridge.hpp"
#include "mqtt/fixed_sink.hpp"

namespace rotord::mqtt {
namespace {

struct CareSensor {
  const char* object;     ///< after "<axis>_"
  const char* name;       ///< after "Azimuth " / "Elevation "
  const char* template_;  ///< %s: the axis ("az", "el")
  const char* unit;       ///< nullptr: none
  const char* icon;
};

constexpr CareSensor kSensors[] = {
    {"starts", "motor starts", "{{ value_json.odometer.%s.starts }}", nullptr, "mdi:counter"},
    {"reversals", "reversals", "{{ value_json.odometer.%s.reversals }}", nullptr,
     "mdi:swap-horizontal"},
    {"run_time", "motor run time", "{{ (value_json.odometer.%s.run_s / 3600) | round(2) }}", "h",
     "mdi:timer-outline"},
    {"turned", "degrees turned", "{{ value_json.odometer.%s.turned_deg }}", "\xc2\xb0",
     "mdi:rotate-right"},
    {"brake_cycles", "brake cycles", "{{ value_json.odometer.%s.brake_cycles }}", nullptr,
     "mdi:car-brake-hold"},
    {"relay_switchings", "relay switchings", "{{ value_json.odometer.%s.relay_switchings }}",
     nullptr, "mdi:electric-switch"},
    {"faults", "faults", "{{ value_json.odometer.%s.faults_total }}", nullptr, "mdi:alert"},
    {"slips", "slips", "{{ value_json.%s.slips }}", nullptr, "mdi:weather-windy"},
};
constexpr int kPerAxis = static_cast<int>(sizeof kSensors / sizeof kSensors[0]);

}  // namespace

bool Bridge::publish_care_sensor(int n) {
  static_assert(2 * kPerAxis == kCareSensorCount, "one announcement per sensor and axis");
  if (n < 0 || n >= kCareSensorCount) return true;
  const bool el = n >= kPerAxis;
  const CareSensor& c = kSensors[n % kPerAxis];
  const char* axis = el ? "el" : "az";
  char topic[kMaxTopicBytes];
  const int tn = std::snprintf(topic, sizeof topic, "homeassistant/sensor/%s/%s_%s/config",
                               node_id_, axis, c.object);
  if (tn <= 0 || static_cast<std::size_t>(tn) >= sizeof topic) return true;
  const std::string_view config_topic(topic, static_cast<std::size_t>(tn));
  // An empty retained config removes an elevation sensor published before.
  if (el && !api_->settings().b(settings::Id::kElEnabled))
    return transport_.publish(config_topic, {}, true);
  char unique_id[80];
  std::snprintf(unique_id, sizeof unique_id, "%s_%s_%s", node_id_, axis, c.object);
  char name[48];
  std::snprintf(name, sizeof name, "%s %s", el ? "Elevation" : "Azimuth", c.name);
  char value_template[80];
  std::snprintf(value_template, sizeof value_template, c.template_, axis);
  char state_topic[kMaxTopicBytes];
  join_topic(prefix(), "state", state_topic, sizeof state_topic);
  FixedSink sink(message_, sizeof message_);
  {
    web::JsonWriter w(sink);
    write_entity_head(w, name, unique_id);
    w.member("state_topic", state_topic)
        .member("value_template", value_template)
        .member("state_class", "total_increasing")
        .member("entity_category", "diagnostic")
        .member("icon", c.icon);
    if (c.unit != nullptr) w.member("unit_of_measurement", c.unit);
    w.end_object();
  }
  if (sink.overflowed()) return true;  // cannot ever fit: not retried
  return transport_.publish(config_topic, sink.view(), true);
}

}  // namespace rotord::mqtt
