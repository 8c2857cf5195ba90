#include "mqtt_client.hpp"

#include <arpa/inet.h>
#include <mosquitto.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "log.hpp"
#include "mqtt/topics.hpp"

namespace rotord::linux_port {
namespace {

using settings::Id;

constexpr std::string_view kOnline = "online";
constexpr std::string_view kOffline = "offline";

std::string text(const settings::Settings& s, Id id) {
  return std::string(s.text(id));
}

/// The address at the other end of the client's socket (the broker), for
/// access.control_networks; an IPv4 peer of an IPv6 socket is IPv4.
access::Peer peer_of_socket(int fd) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (fd < 0 || ::getpeername(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0)
    return {access::Peer::Kind::kOther, 0, {}};
  if (address.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&address);
    return access::Peer::from_ipv4(ntohl(v4->sin_addr.s_addr));
  }
  if (address.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&address);
    access::IpBytes ip{};
    for (std::size_t i = 0; i < ip.size(); ++i) ip[i] = v6->sin6_addr.s6_addr[i];
    return access::Peer::from_ipv6(ip);  // a v4-mapped broker comes back as IPv4
  }
  return {access::Peer::Kind::kOther, 0, {}};
}

}  // namespace

std::unique_ptr<MqttClient> MqttClient::create(const settings::Settings& settings,
                                               const std::string& host_name,
                                               const std::string& web_url, web::Api& api) {
  if (!settings.b(Id::kMqttEnabled)) return nullptr;
  char prefix[mqtt::kMaxPrefixBytes + 1];
  if (mqtt::make_prefix(settings.text(Id::kMqttPrefix), host_name, prefix, sizeof prefix) == 0) {
    log::error(
        "mqtt.prefix '%s' cannot be a topic prefix (no '+', '#' or spaces, no '/' at "
        "either end): MQTT off",
        text(settings, Id::kMqttPrefix).c_str());
    return nullptr;
  }
  std::string client_id = text(settings, Id::kMqttClientId);
  if (client_id.empty()) client_id = "rotord-" + host_name;
  char node_id[48];
  mqtt::make_node_id(client_id, node_id, sizeof node_id);
  std::unique_ptr<MqttClient> client(new MqttClient(
      api, prefix, node_id, "rotord " + (host_name.empty() ? client_id : host_name)));
  client->bridge_.set_web_url(web_url);
  client->bridge_.set_version(ROTORD_VERSION);
  if (!client->start(settings, client_id)) return nullptr;
  return client;
}

MqttClient::MqttClient(web::Api& api, const std::string& prefix, const std::string& node_id,
                       const std::string& device_name)
    : api_(api), bridge_(api, *this, prefix, node_id, device_name) {
  bridge_.set_station(&station_);
  api_.set_station(&station_);
}

bool MqttClient::start(const settings::Settings& settings, const std::string& client_id) {
  static const int lib_init = mosquitto_lib_init();
  (void)lib_init;
  mosq_ = mosquitto_new(client_id.c_str(), true, this);
  if (mosq_ == nullptr) {
    log::error("mqtt: cannot create a client");
    return false;
  }
  mosquitto_threaded_set(mosq_, true);
  const std::string availability(bridge_.availability_topic());
  // The broker says "offline" for us when we vanish (kill -9, power, network).
  mosquitto_will_set(mosq_, availability.c_str(), static_cast<int>(kOffline.size()),
                     kOffline.data(), 1, true);
  const std::string user = text(settings, Id::kMqttUser);
  const std::string password = text(settings, Id::kMqttPassword);
  if (!user.empty())
    mosquitto_username_pw_set(mosq_, user.c_str(), password.empty() ? nullptr : password.c_str());
  if (settings.b(Id::kMqttTls)) {
    // The broker's certificate and its name (mqtt.host) are checked: against
    // mqtt.tls_ca when set, else the system's CAs.
    const std::string ca = text(settings, Id::kMqttTlsCa);
    const int rc =
        ca.empty() ? mosquitto_tls_set(mosq_, nullptr, "/etc/ssl/certs", nullptr, nullptr, nullptr)
                   : mosquitto_tls_set(mosq_, ca.c_str(), nullptr, nullptr, nullptr, nullptr);
    if (rc != MOSQ_ERR_SUCCESS) {
      log::error("mqtt: TLS setup failed (mqtt.tls_ca '%s'): %s: MQTT off",
                 ca.empty() ? "/etc/ssl/certs" : ca.c_str(),
                 rc == MOSQ_ERR_ERRNO ? std::strerror(errno) : mosquitto_strerror(rc));
      return false;
    }
    tls_ = true;
  }
  mosquitto_log_callback_set(mosq_, &MqttClient::on_log);
  mosquitto_connect_callback_set(mosq_, &MqttClient::on_connect);
  mosquitto_disconnect_callback_set(mosq_, &MqttClient::on_disconnect);
  mosquitto_message_callback_set(mosq_, &MqttClient::on_message);
  mosquitto_publish_callback_set(mosq_, &MqttClient::on_publish);
  host_ = text(settings, Id::kMqttHost);
  port_ = settings.i(Id::kMqttPort);
  log::info("mqtt: broker %s:%d, topics %.*s/..., commands %s", host_.c_str(), port_,
            static_cast<int>(bridge_.prefix().size()), bridge_.prefix().data(),
            settings.b(Id::kMqttControl) ? "obeyed" : "stop only");
  thread_ = std::thread([this] { run(); });
  return true;
}

MqttClient::~MqttClient() {
  api_.set_station(nullptr);
  if (mosq_ == nullptr) return;
  if (connected_.load()) {
    // A clean goodbye sends no will: say offline ourselves.
    const std::string availability(bridge_.availability_topic());
    mosquitto_publish(mosq_, nullptr, availability.c_str(), static_cast<int>(kOffline.size()),
                      kOffline.data(), 1, true);
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  mosquitto_disconnect(mosq_);
  if (thread_.joinable()) thread_.join();
  mosquitto_destroy(mosq_);
}

void MqttClient::run() {
  int backoff_s = kMinBackoffS;
  bool first = true;
  bool was_up = false;
  while (!stopping_.load()) {
    // Non-blocking connect: a broker that does not answer cannot hold the
    // thread (or shutdown) for a TCP timeout. Name lookup happens here, off
    // the control loop.
    int rc = first ? mosquitto_connect_async(mosq_, host_.c_str(), port_, kKeepaliveS)
                   : mosquitto_reconnect_async(mosq_);
    first = false;
    if (rc == MOSQ_ERR_SUCCESS) {
      while (!stopping_.load()) {
        rc = mosquitto_loop(mosq_, 100, 1);
        if (rc != MOSQ_ERR_SUCCESS) break;
        if (connected_.load()) {
          backoff_s = kMinBackoffS;
          was_up = true;
        }
      }
    }
    connected_ = false;
    if (stopping_.load()) break;
    // Why, in libmosquitto's words, and OpenSSL's (a certificate that does
    // not verify) when it said more.
    std::string why = rc == MOSQ_ERR_ERRNO ? std::strerror(errno) : mosquitto_strerror(rc);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!library_error_.empty()) why += " (" + library_error_ + ")";
      library_error_.clear();
    }
    if (tls_ && why.find("certificate verify failed") != std::string::npos)
      why += ": is mqtt.tls_ca the CA that signed the broker's certificate, for this mqtt.host?";
    if (was_up) {
      log::warn("mqtt: lost the broker %s:%d (%s); reconnecting", host_.c_str(), port_,
                why.c_str());
      was_up = false;
      last_failure_.clear();
    } else if (why != last_failure_) {
      // Said once, clearly; the same failure again only in the debug log.
      log::warn("mqtt: cannot connect to %s:%d%s: %s; retrying every %d..%d s", host_.c_str(),
                port_, tls_ ? " (TLS)" : "", why.c_str(), kMinBackoffS, kMaxBackoffS);
      last_failure_ = why;
    } else {
      log::debug("mqtt: cannot connect to %s:%d (%s); again in %d s", host_.c_str(), port_,
                 why.c_str(), backoff_s);
    }
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_for(lock, std::chrono::seconds(backoff_s), [this] { return stopping_.load(); });
    backoff_s = backoff_s * 2 > kMaxBackoffS ? kMaxBackoffS : backoff_s * 2;
  }
}

void MqttClient::on_connect(mosquitto* m, void* self, int rc) {
  auto* c = static_cast<MqttClient*>(self);
  if (rc != 0) {
    log::warn("mqtt: the broker refused the connection: %s", mosquitto_connack_string(rc));
    return;
  }
  const std::string availability(c->bridge_.availability_topic());
  mosquitto_publish(m, nullptr, availability.c_str(), static_cast<int>(kOnline.size()),
                    kOnline.data(), 1, true);
  const std::string filter(c->bridge_.command_filter());
  mosquitto_subscribe(m, nullptr, filter.c_str(), 1);
  // The station page: every rotord on a two-level prefix (rotord/<hostname>).
  static const char* const kStation[] = {"+/+/state", "+/+/availability", "+/+/info"};
  for (const char* topic : kStation) mosquitto_subscribe(m, nullptr, topic, 0);
  // The wind stow's topics (a weather station's; docs/care.md).
  for (const std::string_view wind : {c->bridge_.wind_topic(), c->bridge_.wind_dir_topic()}) {
    if (!wind.empty()) mosquitto_subscribe(m, nullptr, std::string(wind).c_str(), 0);
  }
  {
    std::lock_guard<std::mutex> lock(c->mutex_);
    c->broker_peer_ = peer_of_socket(mosquitto_socket(m));
    c->library_error_.clear();
  }
  c->last_failure_.clear();
  log::info("mqtt: connected to %s:%d%s", c->host_.c_str(), c->port_, c->tls_ ? " (TLS)" : "");
  c->connected_ = true;  // the loop republishes discovery and state
}

void MqttClient::on_log(mosquitto* /*m*/, void* self, int level, const char* message) {
  // Errors only: the first of a failed attempt (OpenSSL's reason comes
  // first) is kept for run()'s line. Mostly the network thread's, but a
  // publish from the loop may log too: under the mutex.
  if ((level & (MOSQ_LOG_ERR | MOSQ_LOG_WARNING)) == 0 || message == nullptr) return;
  auto* c = static_cast<MqttClient*>(self);
  std::lock_guard<std::mutex> lock(c->mutex_);
  if (c->library_error_.empty()) c->library_error_ = message;
}

void MqttClient::on_disconnect(mosquitto* /*m*/, void* self, int /*rc*/) {
  static_cast<MqttClient*>(self)->connected_ = false;
}

void MqttClient::on_message(mosquitto* /*m*/, void* self, const mosquitto_message* message) {
  auto* c = static_cast<MqttClient*>(self);
  if (message->topic == nullptr || std::strlen(message->topic) >= mqtt::kMaxTopicBytes) return;
  Inbound in;
  in.topic = message->topic;
  const std::size_t length =
      message->payloadlen > 0 ? static_cast<std::size_t>(message->payloadlen) : 0;
  const bool command = !mqtt::command_name(c->bridge_.prefix(), in.topic).empty();
  if (!command) {
    // Another rotord's topics (or ours echoed), for the station page, and
    // the wind stow's: an oversized wind reading is counted, not dropped.
    if (length > mqtt::Bridge::kMaxStateBytes) {
      if (!c->bridge_.is_wind_topic(in.topic)) return;
      in.oversized = true;
    } else {
      in.payload.assign(static_cast<const char*>(message->payload), length);
    }
    std::lock_guard<std::mutex> lock(c->mutex_);
    if (c->station_inbox_.size() >= kMaxStationInbox) c->station_inbox_.pop_front();
    c->station_inbox_.push_back(std::move(in));
    return;
  }
  if (length > mqtt::Bridge::kMaxCommandBytes) {
    in.oversized = true;  // answered 413, never read
  } else if (length > 0) {
    in.payload.assign(static_cast<const char*>(message->payload), length);
  }
  std::lock_guard<std::mutex> lock(c->mutex_);
  if (c->inbox_.size() >= kMaxInbox) {
    // A flood must not cost a STOP its place: it pushes out the oldest.
    ++c->dropped_;
    if (mqtt::command_name(c->bridge_.prefix(), in.topic) != "stop") return;
    c->inbox_.pop_front();
  }
  c->inbox_.push_back(std::move(in));
}

bool MqttClient::publish(std::string_view topic, std::string_view payload, bool retain) {
  if (!connected_.load()) return false;
  if (unacked_.load() >= kMaxUnacked) {
    if (!publishing_paused_) {
      log::warn(
          "mqtt: the broker %s:%d acknowledges nothing (%d messages waiting): publishing "
          "paused",
          host_.c_str(), port_, kMaxUnacked);
      publishing_paused_ = true;
    }
    ++refused_publishes_;
    return false;
  }
  if (publishing_paused_) {
    log::info("mqtt: the broker %s:%d acknowledges again: publishing resumed", host_.c_str(),
              port_);
    publishing_paused_ = false;
  }
  const std::string t(topic);
  if (mosquitto_publish(mosq_, nullptr, t.c_str(), static_cast<int>(payload.size()), payload.data(),
                        1, retain) != MOSQ_ERR_SUCCESS)
    return false;
  ++unacked_;
  return true;
}

void MqttClient::on_publish(mosquitto* /*m*/, void* self, int /*mid*/) {
  // The broker acknowledged one (or a QoS 0 one went out): never below 0,
  // whatever was queued outside publish().
  auto* c = static_cast<MqttClient*>(self);
  int n = c->unacked_.load();
  while (n > 0 && !c->unacked_.compare_exchange_weak(n, n - 1)) {
  }
}

void MqttClient::poll(Millis wall_ms) {
  // At most kCommandsPerPass commands per 10 ms pass: the rest wait in the
  // bounded inbox, so a flood from the broker costs the loop little.
  std::deque<Inbound> arrived;
  std::deque<Inbound> station;
  std::uint64_t dropped = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (std::size_t n = 0; n < kCommandsPerPass && !inbox_.empty(); ++n) {
      arrived.push_back(std::move(inbox_.front()));
      inbox_.pop_front();
    }
    station.swap(station_inbox_);
    bridge_.set_broker_peer(broker_peer_);
    dropped = dropped_;
  }
  if (dropped != dropped_logged_ &&
      (dropped_logged_ == 0 || wall_ms - dropped_logged_ms_ >= kDropLogGapMs)) {
    // A flood: said at most every kDropLogGapMs, never per message.
    log::warn("mqtt: %llu command(s) dropped: more than %zu waiting (a flood on %.*s/cmd/)",
              static_cast<unsigned long long>(dropped - dropped_logged_), kMaxInbox,
              static_cast<int>(bridge_.prefix().size()), bridge_.prefix().data());
    dropped_logged_ = dropped;
    dropped_logged_ms_ = wall_ms;
  }
  for (const Inbound& in : arrived) bridge_.on_message(in.topic, in.payload, in.oversized);
  for (const Inbound& in : station) bridge_.on_message(in.topic, in.payload, in.oversized);
  bridge_.poll(wall_ms);
}

}  // namespace rotord::linux_port
