#pragma once
// rotord on the station's MQTT broker from the Pico W (docs/mqtt.md): lwIP's
// MQTT client (the pico-sdk's lib/lwip apps/mqtt) under the same portable
// mqtt::Bridge as Linux (topics, state JSON, discovery, commands through the
// REST handlers).
//
// Portable lwIP code with no pico-sdk include, like lwip_transport.cpp: the
// firmware builds it against the SDK's lwIP and tests/lwip against Debian's
// liblwip-dev (with lwIP's mqtt.c from Debian's source of the same version).
// lwIP's callbacks and poll() must run in one context: the Pico's poll loop,
// or with the lwIP core lock held on a NO_SYS=0 host.
//
// RAM: everything is in this object (static in the firmware), nothing is
// allocated: lwIP's client with its buffers (lwip_mqtt_opts.h), the bridge's
// state and message buffers, one incoming command. kStaticBytes below.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lwip_mqtt_opts.h"
#include "mqtt/bridge.hpp"
#include "settings/settings.hpp"
#include "web/web_api.hpp"

// lwIP's headers (C, with Debian's lwipopts.h declaring functions outside
// their extern "C" blocks on the host).
extern "C" {
#include "lwip/apps/mqtt.h"
#include "lwip/apps/mqtt_priv.h"
#include "lwip/ip_addr.h"
#include "lwip/pbuf.h"
#include "lwip/tcp.h"
}

namespace rotord::lwip_port {

class LwipMqtt final : public mqtt::Transport {
 public:
  /// Commands handled per control tick (10 ms): at most 400 a second, as on
  /// Linux. More in one tick are dropped unanswered; a stop never is.
  static constexpr int kCommandsPerTick = 4;
  static constexpr std::uint16_t kKeepaliveS = 30;
  static constexpr Millis kMinBackoffMs = 1000;
  static constexpr Millis kMaxBackoffMs = 30000;

  /// Reads mqtt.* from `settings` once (they take effect after a restart).
  /// `host_name`: the prefix's default (rotord/<host_name>) and the device's
  /// name; `web_url`: this rotord's web UI, for the other rotords' station
  /// pages. Not enabled (logged why) when mqtt.enabled is off or the
  /// settings cannot work (a bad prefix, mqtt.tls: no TLS on the Pico W).
  LwipMqtt(web::Api& api, const settings::Settings& settings, std::string_view host_name,
           std::string_view web_url, const char* version);
  LwipMqtt(const LwipMqtt&) = delete;
  LwipMqtt& operator=(const LwipMqtt&) = delete;

  bool enabled() const { return enabled_; }

  /// Every control tick. `network_up`: the station interface has an
  /// address (a first attempt, and the backoff reset, once it has).
  void poll(Millis now, bool network_up);

  /// A new controller comes with a new API (not on the Pico; tests).
  void set_api(web::Api& api) { bridge_.set_api(api); }

  /// Drops the connection with a TCP reset, no goodbye: what a power cut
  /// looks like to the broker (which then publishes the will). Tests.
  void abort_connection();

  bool connected() const override { return connected_; }
  const mqtt::Bridge& bridge() const { return bridge_; }

  struct Counters {
    std::uint32_t connects = 0;           ///< CONNACKs accepted
    std::uint32_t failed_connects = 0;    ///< refused, unreachable, timed out
    std::uint32_t commands = 0;           ///< handed to the bridge
    std::uint32_t dropped_commands = 0;   ///< over kCommandsPerTick
    std::uint32_t refused_publishes = 0;  ///< lwIP had no room (ring or requests)
  };
  const Counters& counters() const { return counters_; }

 private:
  enum class Phase : std::uint8_t { kIdle, kResolving, kConnecting, kConnected };

  bool publish(std::string_view topic, std::string_view payload, bool retain) override;

  void start_attempt();
  void connect_to(const ip_addr_t& address);
  void failed(const char* why);
  void on_connection(mqtt_connection_status_t status);
  void on_publish_start(const char* topic, std::uint32_t total_bytes);
  void on_publish_data(const std::uint8_t* data, std::uint16_t length, bool last);
  void deliver();

  /// lwIP's client parses a PUBLISH whose header and topic arrive split
  /// across TCP segments wrongly (2.2 closes the connection, 2.1 overwrites
  /// the first part): under a flood from the broker, boundaries fall
  /// anywhere. This shim sits in front of its receive callback and hands it
  /// each message's start whole: a message of up to kWholeMessageBytes
  /// entire, a longer one's first MQTT_VAR_HEADER_BUFFER_LEN bytes.
  static constexpr std::uint32_t kWholeMessageBytes = 1024;
  static err_t recv_shim(void* arg, tcp_pcb* pcb, pbuf* p, err_t err);
  /// How many bytes from the start of held_ may go to lwIP's parser now
  /// (advances in_message_left_ to that point).
  std::uint32_t forwardable(const pbuf* chain);
  void drop_held();

  static void connection_cb(mqtt_client_t* client, void* arg, mqtt_connection_status_t status);
  static void publish_cb(void* arg, const char* topic, std::uint32_t total_bytes);
  static void data_cb(void* arg, const std::uint8_t* data, std::uint16_t length,
                      std::uint8_t flags);
#if LWIP_DNS
  static void dns_cb(const char* name, const ip_addr_t* address, void* arg);
#endif

  /// The names the bridge is built with (computed before it).
  struct Names {
    Names(const settings::Settings& settings, std::string_view host_name);
    char prefix[mqtt::kMaxPrefixBytes + 1] = {};
    char client_id[64] = {};
    char node_id[48] = {};
    char device_name[72] = {};
    bool valid = false;
  };

  /// lwIP's client with a way back to us: its callbacks' `arg` is the
  /// client, the first member (standard layout: the same address).
  struct Link {
    mqtt_client_t client;
    LwipMqtt* owner;
  };

  Names names_;
  mqtt::Bridge bridge_;
  Link link_{};
  mqtt_client_t& client_ = link_.client;
  /// lwIP's receive callback behind recv_shim, and what it holds back.
  tcp_recv_fn mqtt_recv_ = nullptr;
  pbuf* held_ = nullptr;
  std::uint32_t in_message_left_ = 0;  ///< of the message being forwarded
  bool enabled_ = false;
  bool connected_ = false;
  bool was_network_up_ = false;
  Phase phase_ = Phase::kIdle;
  Millis now_ = 0;
  Millis next_attempt_ = 0;
  Millis backoff_ms_ = kMinBackoffMs;
  /// What was last logged of a failed attempt: said once, not every retry.
  const char* last_failure_ = nullptr;
  /// Sent on (re)connection before the bridge's announcements; retried.
  bool online_pending_ = false;
  bool subscribe_pending_ = false;
  int subscribe_step_ = 0;  ///< the next of: commands, wind speed, wind direction
  std::uint16_t port_ = 1883;
  char host_[64] = {};
  char user_[64] = {};
  char password_[64] = {};
  // The incoming message being assembled (lwIP hands it over in pieces).
  bool in_active_ = false;
  bool in_skip_ = false;  ///< not a command topic of ours (or too long): ignored
  bool in_oversized_ = false;
  std::uint32_t in_total_ = 0;
  std::size_t in_len_ = 0;
  char in_topic_[mqtt::kMaxTopicBytes] = {};
  char in_body_[mqtt::Bridge::kMaxCommandBytes] = {};
  int commands_this_tick_ = 0;
  Counters counters_;
};

}  // namespace rotord::lwip_port
