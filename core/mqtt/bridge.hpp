#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/peer.hpp"
#include "mqtt/station.hpp"
#include "mqtt/topics.hpp"
#include "settings/preset.hpp"
#include "util/time.hpp"
#include "web/web_api.hpp"

namespace rotord::mqtt {

/// What a port's MQTT client offers the bridge (libmosquitto on Linux,
/// lwIP's MQTT app on the Pico W). publish() only queues: it never blocks.
class Transport {
 public:
  virtual ~Transport() = default;
  virtual bool connected() const = 0;
  /// QoS 1. False: not queued (not connected, or the client's queue is full).
  virtual bool publish(std::string_view topic, std::string_view payload, bool retain) = 0;
};

/// The portable half of MQTT (docs/mqtt.md): the retained state on
/// <prefix>/state, commands on <prefix>/cmd/<name> answered on
/// <prefix>/result through the REST API's own handlers (same bodies, same
/// validation, same errors), and Home Assistant discovery. Runs in the
/// control loop's thread; every buffer is a member, nothing is allocated.
class Bridge {
 public:
  /// A command body larger than this is refused (413), unread.
  static constexpr std::size_t kMaxCommandBytes = 512;
  /// GET /api/status of an az/el rotator is about 2 KB.
  static constexpr std::size_t kMaxStateBytes = 3072;
  /// One discovery config message.
  static constexpr std::size_t kMaxDiscoveryBytes = 1024;
  /// The fastest the state is ever published (mqtt.state_hz's maximum).
  static constexpr Millis kMinStateGapMs = 100;
  /// A standing rotator's position must change this much to be published
  /// (a pot's noise is not a change); while moving, mqtt.state_hz rules.
  static constexpr float kPositionStepDeg = 0.5f;

  /// `prefix` and `node_id` are copied.
  Bridge(web::Api& api, Transport& transport, std::string_view prefix, std::string_view node_id,
         std::string_view device_name);

  /// Where this rotord's web UI is (published retained on <prefix>/info for
  /// the other rotords' station pages); copied.
  void set_web_url(std::string_view url);
  /// Messages that are not commands go to `station` (the port subscribes to
  /// the other rotords' topics); nullptr: ignored.
  void set_station(Station* station) { station_ = station; }

  /// rotord's version for <prefix>/info and discovery's sw_version (the
  /// port's ROTORD_VERSION); not copied: a string literal.
  void set_version(const char* version) { version_ = version; }

  /// The broker's address as the port's client connected to it: commands
  /// are refused (403) unless access.control_networks lets it control, as
  /// for a line-protocol client at that address. Until told: an address the
  /// allow-list cannot name (read-only whenever the list is set).
  void set_broker_peer(const access::Peer& peer) { broker_peer_ = peer; }

  /// A new controller (POST /api/reboot) comes with a new API.
  void set_api(web::Api& api) { api_ = &api; }

  std::string_view prefix() const { return {prefix_, prefix_len_}; }
  std::string_view availability_topic() const { return {availability_, availability_len_}; }
  std::string_view command_filter() const { return {command_filter_, command_filter_len_}; }
  /// The wind stow's topics (wind.mqtt_topic, wind.mqtt_dir_topic, read at
  /// construction: they take effect after a restart), empty when unset; the
  /// port subscribes to them (docs/care.md, "Wind stow").
  std::string_view wind_topic() const { return wind_topic_; }
  std::string_view wind_dir_topic() const { return wind_dir_topic_; }
  /// Whether `topic` is one of them: the port delivers its messages even
  /// when not a command (an oversized one is counted as garbage).
  bool is_wind_topic(std::string_view topic) const {
    return !topic.empty() && (topic == wind_topic() || topic == wind_dir_topic());
  }

  /// Called on every pass of the loop with the transport's clock: publishes
  /// the state when it changed, at mqtt.state_hz while moving, and
  /// everything again (discovery, info, state) after a (re)connection. A
  /// publish the transport refuses (its queue full) is tried again on a
  /// later pass: the announcements in order, then the state.
  void poll(Millis now_ms);

  /// A message arrived on a subscribed topic. `oversized`: the port dropped
  /// a payload larger than kMaxCommandBytes (answered 413).
  void on_message(std::string_view topic, std::string_view payload, bool oversized = false);

  /// Messages published (state, results, discovery) and commands handled.
  std::uint32_t states_published() const { return states_published_; }
  std::uint32_t commands_handled() const { return commands_handled_; }

 private:
  /// What makes a state worth publishing at once (not the clock).
  struct Fingerprint {
    int mode = -1;
    int speed_pct = 0;
    bool fault = false;
    bool lock = false;
    bool az_valid = false, el_valid = false;
    int az_target_tenths = 0, el_target_tenths = 0;
    bool az_target = false, el_target = false;
    int az_state = 0, el_state = 0, az_fault = 0, el_fault = 0;
    int wind_state = 0;
    bool operator==(const Fingerprint&) const = default;
  };
  Fingerprint fingerprint() const;
  /// Whether a position moved by kPositionStepDeg since the last publish.
  bool position_changed() const;
  bool publish_state();
  /// Discovery's entities, a button per preset slot, then <prefix>/info.
  static constexpr int kEntityCount = 7;
  /// The wear odometer's and the slips' sensors (care_sensors.cpp), per axis.
  static constexpr int kCareSensorCount = 16;
  static constexpr int kAnnouncements =
      kEntityCount + static_cast<int>(settings::kPresetCount) + kCareSensorCount + 1;
  /// Publishes announcement `step` (0..kAnnouncements-1); false: the
  /// transport refused it (tried again later).
  bool announce(int step);
  bool publish_discovery(int entity);
  /// What entity `entity` (0..kEntityCount-1) has beyond the head: its
  /// topics, templates and units.
  void write_entity_body(web::JsonWriter& w, int entity) const;
  bool publish_info();
  /// Home Assistant's button for preset slot `slot` (an empty config
  /// removes the button of an unused slot); presets.cpp.
  bool publish_preset_button(int slot);
  /// Home Assistant's sensor `n` of the wear odometer and the slips
  /// (docs/care.md); the elevation's are removed on an azimuth-only rotator.
  bool publish_care_sensor(int n);
  /// The device, availability, name and unique id every entity has.
  void write_entity_head(web::JsonWriter& w, const char* name, const char* unique_id) const;
  /// Whether the presets changed since the last call (their buttons are
  /// announced again).
  bool presets_changed();
  void publish_result(std::string_view command, int status, std::string_view body);

  web::Api* api_;
  Transport& transport_;
  char prefix_[kMaxPrefixBytes + 1] = {};
  std::size_t prefix_len_ = 0;
  char node_id_[48] = {};
  char device_name_[72] = {};
  char web_url_[Station::kMaxUrlBytes] = {};
  Station* station_ = nullptr;
  access::Peer broker_peer_{access::Peer::Kind::kOther, 0, {}};
  const char* version_ = "";
  char availability_[kMaxTopicBytes] = {};
  std::size_t availability_len_ = 0;
  char command_filter_[kMaxTopicBytes] = {};
  // wind.mqtt_topic and wind.mqtt_dir_topic hold at most 63 bytes (RAM).
  char wind_topic_[64] = {};
  char wind_dir_topic_[64] = {};
  std::size_t command_filter_len_ = 0;
  bool was_connected_ = false;
  int announce_step_ = kAnnouncements;  ///< the next announcement to publish
  bool have_published_ = false;
  Fingerprint last_;
  std::uint32_t presets_crc_ = 0;
  std::uint32_t presets_revision_ = 0;
  bool presets_revision_valid_ = false;
  float last_az_deg_ = 0.0f;
  float last_el_deg_ = 0.0f;
  Millis last_publish_ms_ = 0;
  std::uint32_t states_published_ = 0;
  std::uint32_t commands_handled_ = 0;
  /// The state's JSON; also a command's HTTP response from the API (the
  /// state is rendered anew for each publish, so they never overlap).
  char state_[kMaxStateBytes];
  /// A result, discovery or info message.
  char message_[kMaxDiscoveryBytes];
  char topic_[kMaxTopicBytes];
};

}  // namespace rotord::mqtt
