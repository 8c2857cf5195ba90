#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "mqtt/bridge.hpp"
#include "settings/settings.hpp"
#include "web/web_api.hpp"

struct mosquitto;
struct mosquitto_message;

namespace rotord::linux_port {

/// rotord on the station's MQTT broker (docs/mqtt.md) through Debian's
/// libmosquitto. The network lives in a thread of its own that connects,
/// reads and reconnects with backoff (1 s doubling to 30 s); the control
/// loop only drains a bounded inbox and queues publishes in poll(), so a
/// broker that is down or slow never stalls the tick or the other protocols.
class MqttClient final : private mqtt::Transport {
 public:
  /// Messages waiting for the loop; more are dropped (and counted).
  static constexpr std::size_t kMaxInbox = 16;
  /// Commands handled per pass of the loop (10 ms): at most 400 a second.
  static constexpr std::size_t kCommandsPerPass = 4;
  static constexpr int kKeepaliveS = 30;
  static constexpr int kMinBackoffS = 1;
  static constexpr int kMaxBackoffS = 30;

  /// Other rotords' state messages waiting; more are dropped.
  static constexpr std::size_t kMaxStationInbox = 32;
  /// Messages handed to libmosquitto and not yet acknowledged by the broker
  /// (QoS 1); beyond this a publish is refused (a result dropped, the state
  /// sent on a later pass), so a broker that reads slowly cannot make the
  /// outgoing queue grow without bound.
  static constexpr int kMaxUnacked = 64;
  /// A flood's dropped commands are logged at most this often.
  static constexpr Millis kDropLogGapMs = 10000;

  /// nullptr when mqtt.enabled is off or the settings cannot work (logged).
  /// `web_url`: where this rotord's web UI is, for the station pages.
  static std::unique_ptr<MqttClient> create(const settings::Settings& settings,
                                            const std::string& host_name,
                                            const std::string& web_url, web::Api& api);
  ~MqttClient() override;
  MqttClient(const MqttClient&) = delete;
  MqttClient& operator=(const MqttClient&) = delete;

  /// From the control loop: hands over the commands that arrived, publishes
  /// the state when due (mqtt::Bridge::poll).
  void poll(Millis wall_ms);

 private:
  struct Inbound {
    std::string topic, payload;
    bool oversized = false;
  };
  MqttClient(web::Api& api, const std::string& prefix, const std::string& node_id,
             const std::string& device_name);
  bool start(const settings::Settings& settings, const std::string& client_id);
  void run();
  bool connected() const override { return connected_.load(); }
  bool publish(std::string_view topic, std::string_view payload, bool retain) override;

  static void on_connect(mosquitto* m, void* self, int rc);
  static void on_disconnect(mosquitto* m, void* self, int rc);
  static void on_log(mosquitto* m, void* self, int level, const char* message);
  static void on_publish(mosquitto* m, void* self, int mid);
  static void on_message(mosquitto* m, void* self, const mosquitto_message* message);

  web::Api& api_;
  mqtt::Station station_;  ///< every rotord seen on the broker (GET /api/station)
  mqtt::Bridge bridge_;
  mosquitto* mosq_ = nullptr;
  std::string host_;
  int port_ = 1883;
  bool tls_ = false;
  /// libmosquitto's first error of this attempt (on_log; guarded by
  /// mutex_), and the network thread's last failure logged (said once, not
  /// at every retry).
  std::string library_error_;
  std::string last_failure_;
  std::thread thread_;
  std::atomic<bool> connected_{false};
  std::atomic<bool> stopping_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Inbound> inbox_;
  std::deque<Inbound> station_inbox_;
  std::uint64_t dropped_ = 0;         ///< commands the full inbox had no room for (mutex_)
  std::uint64_t dropped_logged_ = 0;  ///< the loop's: dropped_ when last logged
  Millis dropped_logged_ms_ = 0;
  std::atomic<int> unacked_{0};
  std::uint64_t refused_publishes_ = 0;  ///< the loop's: kMaxUnacked reached
  bool publishing_paused_ = false;       ///< the loop's: said so in the log
  /// The broker's address of the current connection (on_connect), for
  /// access.control_networks; guarded by mutex_.
  access::Peer broker_peer_{access::Peer::Kind::kOther, 0, {}};
};

}  // namespace rotord::linux_port
