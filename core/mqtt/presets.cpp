// Home Assistant buttons for the presets (issue 26): one per preset slot,
// pressing it publishes {"name": ...} on <prefix>/cmd/preset, which turns the
// beam through POST /api/preset. An unused slot's config is empty, which
// removes a button published before.
#include <cstdio>

#include "json/json_writer.hpp"
#include "mqtt/bridge.hpp"
#include "mqtt/fixed_sink.hpp"
#include "util/crc32.hpp"

namespace rotord::mqtt {

void Bridge::write_entity_head(web::JsonWriter& w, const char* name, const char* unique_id) const {
  w.begin_object()
      .member("name", name)
      .member("unique_id", unique_id)
      .member("availability_topic", availability_topic())
      .member("payload_available", "online")
      .member("payload_not_available", "offline");
  w.key("device")
      .begin_object()
      .key("identifiers")
      .begin_array()
      .string(node_id_)
      .end_array()
      .member("name", device_name_)
      .member("manufacturer", "rotord")
      .member("model", "rotord antenna rotator controller")
      .member("sw_version", version_)
      .end_object();
}

bool Bridge::presets_changed() {
  const settings::Settings& s = api_->settings();
  // Looked at only when some setting changed (the CRC is bit by bit).
  if (presets_revision_valid_ && s.revision() == presets_revision_) return false;
  presets_revision_ = s.revision();
  presets_revision_valid_ = true;
  std::uint32_t crc = 0;
  for (std::size_t n = 0; n < settings::kPresetCount; ++n) {
    const std::string_view row = s.text(settings::preset_id(n));
    crc = crc32(row.data(), row.size(), crc);
    crc = crc32("\n", 1, crc);
  }
  const bool changed = crc != presets_crc_;
  presets_crc_ = crc;
  return changed;
}

bool Bridge::publish_preset_button(int slot) {
  char topic[kMaxTopicBytes];
  const int tn = std::snprintf(topic, sizeof topic, "homeassistant/button/%s/preset_%d/config",
                               node_id_, slot + 1);
  if (tn <= 0 || static_cast<std::size_t>(tn) >= sizeof topic) return true;
  const std::string_view config_topic(topic, static_cast<std::size_t>(tn));
  settings::Preset p;
  const std::string_view row =
      api_->settings().text(settings::preset_id(static_cast<std::size_t>(slot)));
  if (settings::parse_preset(row, p) != nullptr) return transport_.publish(config_topic, {}, true);
  char command_topic[kMaxTopicBytes];
  join_topic(prefix(), "cmd/preset", command_topic, sizeof command_topic);
  char unique_id[72];
  std::snprintf(unique_id, sizeof unique_id, "%s_preset_%d", node_id_, slot + 1);
  char name[48];
  std::snprintf(name, sizeof name, "Turn to %s (%.0f\xc2\xb0%s)", p.name, p.az_deg,
                p.long_path ? " LP" : "");
  FixedSink sink(message_, sizeof message_);
  {
    web::JsonWriter w(sink);
    write_entity_head(w, name, unique_id);
    w.member("command_topic", command_topic).key("payload_press");
    // {"name": "<preset>"}, the name escaped as JSON by a writer of its own.
    char payload[64];
    FixedSink payload_sink(payload, sizeof payload);
    {
      web::JsonWriter pw(payload_sink);
      pw.begin_object().member("name", p.name).end_object();
    }
    w.string(payload_sink.view()).member("icon", "mdi:compass-rose").end_object();
  }
  if (sink.overflowed()) return true;  // cannot ever fit: not retried
  return transport_.publish(config_topic, sink.view(), true);
}

}  // namespace rotord::mqtt
