#include "lwip_mqtt.hpp"

#include <cstdio>
#include <cstring>
#include <type_traits>

#include "mqtt/topics.hpp"

extern "C" {
#include "lwip/def.h"
#include "lwip/err.h"
#include "lwip/tcp.h"
#if LWIP_DNS
#include "lwip/dns.h"
#endif
}

namespace rotord::lwip_port {
namespace {

using settings::Id;

constexpr char kOnline[] = "online";
constexpr char kOffline[] = "offline";

// The largest message must fit lwIP's output ring whole (lwip_mqtt_opts.h):
// a PUBLISH's fixed header (<= 5), topic length (2), topic, packet id (2).
static_assert(MQTT_OUTPUT_RINGBUF_SIZE >=
                  mqtt::Bridge::kMaxStateBytes + mqtt::kMaxTopicBytes + 5 + 2 + 2,
              "lwIP's MQTT output buffer cannot hold the largest state message");
static_assert(MQTT_VAR_HEADER_BUFFER_LEN >= mqtt::kMaxTopicBytes + 5 + 2 + 2,
              "lwIP's MQTT receive buffer cannot hold a command topic");

static_assert(!LWIP_ALTCP, "recv_shim sits on a plain tcp_pcb");

void copy_text(std::string_view from, char* out, std::size_t cap) {
  const std::size_t n = from.size() < cap - 1 ? from.size() : cap - 1;
  if (n > 0) std::memcpy(out, from.data(), n);
  out[n] = '\0';
}

const char* status_text(mqtt_connection_status_t status) {
  switch (status) {
    case MQTT_CONNECT_ACCEPTED:
      return "accepted";
    case MQTT_CONNECT_REFUSED_PROTOCOL_VERSION:
      return "the broker refused: protocol version";
    case MQTT_CONNECT_REFUSED_IDENTIFIER:
      return "the broker refused the client id (mqtt.client_id)";
    case MQTT_CONNECT_REFUSED_SERVER:
      return "the broker refused: server unavailable";
    case MQTT_CONNECT_REFUSED_USERNAME_PASS:
      return "the broker refused the user name or password (mqtt.user, mqtt.password)";
    case MQTT_CONNECT_REFUSED_NOT_AUTHORIZED_:
      return "the broker refused: not authorized (mqtt.user)";
    case MQTT_CONNECT_DISCONNECTED:
      return "disconnected";
    case MQTT_CONNECT_TIMEOUT:
      return "no answer from the broker";
  }
  return "failed";
}

}  // namespace

LwipMqtt::Names::Names(const settings::Settings& settings, std::string_view host_name) {
  valid = mqtt::make_prefix(settings.text(Id::kMqttPrefix), host_name, prefix, sizeof prefix) != 0;
  const std::string_view id = settings.text(Id::kMqttClientId);
  if (id.empty()) {
    std::snprintf(client_id, sizeof client_id, "rotord-%.*s", static_cast<int>(host_name.size()),
                  host_name.data());
  } else {
    copy_text(id, client_id, sizeof client_id);
  }
  mqtt::make_node_id(client_id, node_id, sizeof node_id);
  std::snprintf(device_name, sizeof device_name, "rotord %.*s", static_cast<int>(host_name.size()),
                host_name.data());
}

LwipMqtt::LwipMqtt(web::Api& api, const settings::Settings& settings, std::string_view host_name,
                   std::string_view web_url, const char* version)
    : names_(settings, host_name),
      bridge_(api, *this, names_.prefix, names_.node_id, names_.device_name) {
  static_assert(std::is_standard_layout_v<Link>, "the client must start the Link");
  link_.owner = this;
  bridge_.set_web_url(web_url);
  bridge_.set_version(version);
  if (!settings.b(Id::kMqttEnabled)) return;
  if (!names_.valid) {
    std::printf(
        "rotord: mqtt.prefix cannot be a topic prefix (no '+', '#' or spaces, no '/' at either "
        "end): MQTT off\n");
    return;
  }
  if (settings.b(Id::kMqttTls)) {
    std::printf("rotord: mqtt.tls: the Pico W has no TLS to the broker: MQTT off\n");
    return;
  }
  copy_text(settings.text(Id::kMqttHost), host_, sizeof host_);
  copy_text(settings.text(Id::kMqttUser), user_, sizeof user_);
  copy_text(settings.text(Id::kMqttPassword), password_, sizeof password_);
  port_ = static_cast<std::uint16_t>(settings.i(Id::kMqttPort));
  enabled_ = true;
  std::printf("rotord: mqtt: broker %s:%u, topics %s/..., commands %s\n", host_,
              static_cast<unsigned>(port_), names_.prefix,
              settings.b(Id::kMqttControl) ? "obeyed" : "stop only");
}

void LwipMqtt::poll(Millis now, bool network_up) {
  now_ = now;
  commands_this_tick_ = 0;
  if (!enabled_) return;
  if (network_up && !was_network_up_) {
    // The network came (back): try at once, from the shortest backoff.
    backoff_ms_ = kMinBackoffMs;
    next_attempt_ = now;
  }
  was_network_up_ = network_up;
  if (in_active_ && in_total_ == 0) deliver();  // an empty message lwIP gave no data call for
  if (phase_ == Phase::kIdle && network_up && now >= next_attempt_) start_attempt();
  if (phase_ != Phase::kConnected) {
    bridge_.poll(now);  // sees the connection gone: everything again on the next
    return;
  }
  if (subscribe_pending_) {
    // Commands, then the wind stow's topics (a weather station's, QoS 0);
    // the station page (other rotords' topics) is Linux's. One a pass, each
    // tried again on a later pass while lwIP's queue is full.
    const std::string_view topics[] = {bridge_.command_filter(), bridge_.wind_topic(),
                                       bridge_.wind_dir_topic()};
    while (subscribe_step_ < 3 && topics[subscribe_step_].empty()) ++subscribe_step_;
    if (subscribe_step_ < 3 &&
        mqtt_subscribe(&client_, topics[subscribe_step_].data(), subscribe_step_ == 0 ? 1 : 0,
                       nullptr, nullptr) == ERR_OK)
      ++subscribe_step_;
    subscribe_pending_ = subscribe_step_ < 3;
  }
  if (online_pending_) {
    const std::string_view topic = bridge_.availability_topic();
    online_pending_ = mqtt_publish(&client_, topic.data(), kOnline, sizeof kOnline - 1, 1, 1,
                                   nullptr, nullptr) != ERR_OK;
    if (online_pending_) return;  // availability first, then the rest
  }
  bridge_.poll(now);
}

void LwipMqtt::start_attempt() {
  ip_addr_t address;
  if (ipaddr_aton(host_, &address)) {
    connect_to(address);
    return;
  }
#if LWIP_DNS
  phase_ = Phase::kResolving;
  const err_t err = dns_gethostbyname(host_, &address, &LwipMqtt::dns_cb, this);
  if (err == ERR_OK) {
    connect_to(address);
  } else if (err != ERR_INPROGRESS) {
    failed("cannot look up mqtt.host");
  }
#else
  failed("mqtt.host is not an IPv4 address (this lwIP has no DNS)");
#endif
}

#if LWIP_DNS
void LwipMqtt::dns_cb(const char* /*name*/, const ip_addr_t* address, void* arg) {
  auto* self = static_cast<LwipMqtt*>(arg);
  if (self->phase_ != Phase::kResolving) return;
  if (address == nullptr) {
    self->failed("mqtt.host not found (DNS)");
  } else {
    self->connect_to(*address);
  }
}
#endif

void LwipMqtt::connect_to(const ip_addr_t& address) {
  mqtt_connect_client_info_t info{};  // will_msg_len (lwIP 2.2) 0: strlen(will_msg)
  info.client_id = names_.client_id;
  info.client_user = user_[0] != '\0' ? user_ : nullptr;
  info.client_pass = user_[0] != '\0' && password_[0] != '\0' ? password_ : nullptr;
  info.keep_alive = kKeepaliveS;
  // The broker says "offline" for us when we vanish (power, network).
  info.will_topic = bridge_.availability_topic().data();  // NUL-terminated in the bridge
  info.will_msg = kOffline;
  info.will_qos = 1;
  info.will_retain = 1;
  // access.control_networks applies to the broker's address, as on Linux.
  if (IP_IS_V4_VAL(address)) {
    bridge_.set_broker_peer(
        access::Peer::from_ipv4(lwip_ntohl(ip4_addr_get_u32(ip_2_ip4(&address)))));
  } else {
    bridge_.set_broker_peer({access::Peer::Kind::kOther, 0, {}});
  }
  phase_ = Phase::kConnecting;
  const err_t err =
      mqtt_client_connect(&client_, &address, port_, &LwipMqtt::connection_cb, this, &info);
  if (err != ERR_OK) {
    failed("cannot open a connection to the broker");
    return;
  }
  // After connecting: lwIP 2.1's mqtt_client_connect clears the callbacks.
  mqtt_set_inpub_callback(&client_, &LwipMqtt::publish_cb, &LwipMqtt::data_cb, this);
}

void LwipMqtt::failed(const char* why) {
  ++counters_.failed_connects;
  const bool was_connected = connected_;
  connected_ = false;
  phase_ = Phase::kIdle;
  in_active_ = false;
  next_attempt_ = now_ + backoff_ms_;
  if (was_connected) {
    std::printf("rotord: mqtt: lost the broker %s:%u (%s); reconnecting\n", host_,
                static_cast<unsigned>(port_), why);
    last_failure_ = nullptr;
  } else if (why != last_failure_) {
    std::printf("rotord: mqtt: cannot connect to %s:%u: %s; retrying every %d..%d s\n", host_,
                static_cast<unsigned>(port_), why, static_cast<int>(kMinBackoffMs / 1000),
                static_cast<int>(kMaxBackoffMs / 1000));
    last_failure_ = why;
  }
  backoff_ms_ = backoff_ms_ * 2 > kMaxBackoffMs ? kMaxBackoffMs : backoff_ms_ * 2;
}

void LwipMqtt::connection_cb(mqtt_client_t* /*client*/, void* arg,
                             mqtt_connection_status_t status) {
  static_cast<LwipMqtt*>(arg)->on_connection(status);
}

void LwipMqtt::on_connection(mqtt_connection_status_t status) {
  if (status != MQTT_CONNECT_ACCEPTED) {
    drop_held();
    // lwIP may report one failure twice (the CONNACK, then the close).
    if (phase_ == Phase::kIdle) return;
    failed(status_text(status));
    return;
  }
  // lwIP set its receive callback when TCP connected; the CONNACK (this
  // call) is the first message, so nothing is in flight behind it yet.
  if (client_.conn != nullptr && client_.conn->recv != &LwipMqtt::recv_shim) {
    mqtt_recv_ = client_.conn->recv;
    tcp_recv(client_.conn, &LwipMqtt::recv_shim);
  }
  in_message_left_ = 0;
  phase_ = Phase::kConnected;
  connected_ = true;
  backoff_ms_ = kMinBackoffMs;
  last_failure_ = nullptr;
  ++counters_.connects;
  // Subscribe and say online from poll(): lwIP's queue may need a pass.
  subscribe_pending_ = true;
  subscribe_step_ = 0;
  online_pending_ = true;
  std::printf("rotord: mqtt: connected to %s:%u\n", host_, static_cast<unsigned>(port_));
}

err_t LwipMqtt::recv_shim(void* arg, tcp_pcb* pcb, pbuf* p, err_t err) {
  // arg is lwIP's client, the first member of our Link.
  LwipMqtt* self = reinterpret_cast<Link*>(static_cast<mqtt_client_t*>(arg))->owner;
  const tcp_recv_fn parse = self->mqtt_recv_;
  if (p == nullptr || err != ERR_OK) {
    self->drop_held();
    return parse(arg, pcb, p, err);
  }
  if (self->held_ == nullptr) {
    self->held_ = p;
  } else {
    pbuf_cat(self->held_, p);
  }
  pbuf* held = self->held_;
  const std::uint32_t ready = self->forwardable(held);
  if (ready == 0) return ERR_OK;  // a message's start is still incomplete
  pbuf* out = held;
  self->held_ = nullptr;
  if (ready < held->tot_len) {
    // Split the chain: what is ready goes to the parser, the rest waits.
    const auto rest_len = static_cast<std::uint16_t>(held->tot_len - ready);
    out = pbuf_alloc(PBUF_RAW, static_cast<std::uint16_t>(ready), PBUF_RAM);
    pbuf* rest = pbuf_alloc(PBUF_RAW, rest_len, PBUF_RAM);
    if (out == nullptr || rest == nullptr) {
      // No memory to split: hand it all over, as without the shim.
      if (out != nullptr) pbuf_free(out);
      if (rest != nullptr) pbuf_free(rest);
      out = held;
      self->in_message_left_ = 0;
    } else {
      pbuf_copy_partial(held, out->payload, static_cast<std::uint16_t>(ready), 0);
      pbuf_copy_partial(held, rest->payload, rest_len, static_cast<std::uint16_t>(ready));
      pbuf_free(held);
      self->held_ = rest;  // before parsing: a close in there frees it
    }
  }
  return parse(arg, pcb, out, ERR_OK);
}

std::uint32_t LwipMqtt::forwardable(const pbuf* chain) {
  const std::uint32_t len = chain->tot_len;
  std::uint32_t pos = 0;
  std::uint32_t left = in_message_left_;
  const auto at = [chain](std::uint32_t i) {
    return pbuf_get_at(chain, static_cast<std::uint16_t>(i));
  };
  while (pos < len) {
    if (left > 0) {
      const std::uint32_t take = left < len - pos ? left : len - pos;
      pos += take;
      left -= take;
      continue;
    }
    // A message starts at pos: its fixed header, then how much of it lwIP's
    // parser must see in one piece.
    std::uint32_t remaining = 0;
    std::uint32_t header = 0;
    for (std::uint32_t i = 1; i <= 4; ++i) {
      if (pos + i >= len) break;
      const std::uint8_t b = at(pos + i);
      remaining |= static_cast<std::uint32_t>(b & 0x7f) << (7 * (i - 1));
      if ((b & 0x80) == 0) {
        header = i + 1;
        break;
      }
      if (i == 4) {
        // Not MQTT: let lwIP's parser say so (it closes the connection).
        in_message_left_ = 0;
        return len;
      }
    }
    if (header == 0) break;  // the header itself is incomplete
    // Whole up to kWholeMessageBytes; of a longer one (a PUBLISH: nothing
    // else the broker sends is that long) the part lwIP's parser buffers
    // first, which holds its header and topic. So at most ~1 KB is held
    // back, whatever the stream says.
    const std::uint32_t total = header + remaining;
    static_assert(kWholeMessageBytes >= MQTT_VAR_HEADER_BUFFER_LEN, "");
    const std::uint32_t need = total <= kWholeMessageBytes ? total : MQTT_VAR_HEADER_BUFFER_LEN;
    if (len - pos < need) break;
    left = total;
  }
  in_message_left_ = left;
  return pos;
}

void LwipMqtt::drop_held() {
  if (held_ != nullptr) pbuf_free(held_);
  held_ = nullptr;
  in_message_left_ = 0;
}

void LwipMqtt::abort_connection() {
  if (client_.conn != nullptr) tcp_abort(client_.conn);
}

bool LwipMqtt::publish(std::string_view topic, std::string_view payload, bool retain) {
  if (!connected_ || payload.size() > 0xffff) return false;
  char t[mqtt::kMaxTopicBytes];
  if (topic.size() >= sizeof t) return false;
  std::memcpy(t, topic.data(), topic.size());
  t[topic.size()] = '\0';
  const err_t err =
      mqtt_publish(&client_, t, payload.data(), static_cast<std::uint16_t>(payload.size()), 1,
                   retain ? 1 : 0, nullptr, nullptr);
  if (err != ERR_OK) {
    ++counters_.refused_publishes;
    return false;
  }
  return true;
}

void LwipMqtt::publish_cb(void* arg, const char* topic, std::uint32_t total_bytes) {
  static_cast<LwipMqtt*>(arg)->on_publish_start(topic, total_bytes);
}

void LwipMqtt::data_cb(void* arg, const std::uint8_t* data, std::uint16_t length,
                       std::uint8_t flags) {
  static_cast<LwipMqtt*>(arg)->on_publish_data(data, length, (flags & MQTT_DATA_FLAG_LAST) != 0);
}

void LwipMqtt::on_publish_start(const char* topic, std::uint32_t total_bytes) {
  if (in_active_ && in_total_ == 0) deliver();  // an empty one before it
  in_active_ = true;
  in_total_ = total_bytes;
  in_len_ = 0;
  const std::size_t topic_len = topic != nullptr ? std::strlen(topic) : sizeof in_topic_;
  // Commands, and the wind stow's topics (docs/care.md); the rest is not ours.
  in_skip_ = topic_len >= sizeof in_topic_ ||
             (mqtt::command_name(bridge_.prefix(), std::string_view(topic, topic_len)).empty() &&
              !bridge_.is_wind_topic(std::string_view(topic, topic_len)));
  if (!in_skip_) std::memcpy(in_topic_, topic, topic_len + 1);
  // A body over the limit is answered 413 and never stored.
  in_oversized_ = total_bytes > mqtt::Bridge::kMaxCommandBytes;
}

void LwipMqtt::on_publish_data(const std::uint8_t* data, std::uint16_t length, bool last) {
  if (!in_active_) return;
  if (!in_skip_ && !in_oversized_ && length > 0) {
    if (in_len_ + length > sizeof in_body_) {
      in_oversized_ = true;
    } else {
      std::memcpy(in_body_ + in_len_, data, length);
      in_len_ += length;
    }
  }
  if (last) deliver();
}

void LwipMqtt::deliver() {
  in_active_ = false;
  if (in_skip_) return;
  const std::string_view topic(in_topic_);
  if (bridge_.is_wind_topic(topic)) {
    // A weather station's reading, not a command: outside the commands' budget.
    bridge_.on_message(topic, std::string_view(in_body_, in_oversized_ ? 0 : in_len_),
                       in_oversized_);
    return;
  }
  if (commands_this_tick_ >= kCommandsPerTick &&
      mqtt::command_name(bridge_.prefix(), topic) != "stop") {
    ++counters_.dropped_commands;  // a flood: a stop still gets through
    return;
  }
  ++commands_this_tick_;
  ++counters_.commands;
  bridge_.on_message(topic, std::string_view(in_body_, in_oversized_ ? 0 : in_len_), in_oversized_);
}

}  // namespace rotord::lwip_port
