#include "avahi_publisher.hpp"

#include <avahi-client/client.h>
#include <avahi-client/publish.h>
#include <avahi-common/alternative.h>
#include <avahi-common/error.h>
#include <avahi-common/malloc.h>
#include <avahi-common/thread-watch.h>
#include <avahi-common/timeval.h>

#include "log.hpp"

namespace rotord::linux_port {

struct AvahiCallbacks {
  static void client(AvahiClient* client, AvahiClientState state, void* self) {
    static_cast<AvahiPublisher*>(self)->on_client(client, state);
  }
  static void group(AvahiEntryGroup* group, AvahiEntryGroupState state, void* self) {
    static_cast<AvahiPublisher*>(self)->on_group(group, state);
  }
  static void retry(AvahiTimeout*, void* self) { static_cast<AvahiPublisher*>(self)->connect(); }
};

AvahiPublisher::AvahiPublisher(const net::ServicePorts& ports, std::string version)
    : ports_(ports), version_(std::move(version)) {
  if (ports_.web == 0 && ports_.rotctld == 0) return;  // nothing to announce
  poll_ = avahi_threaded_poll_new();
  if (poll_ == nullptr) {
    log::warn("avahi: cannot create its event thread; rotord is not announced on the network");
    return;
  }
  connect();
  if (avahi_threaded_poll_start(poll_) < 0) {
    log::warn("avahi: cannot start its event thread; rotord is not announced on the network");
    if (client_ != nullptr) avahi_client_free(client_);
    client_ = nullptr;
    if (retry_ != nullptr) avahi_threaded_poll_get(poll_)->timeout_free(retry_);
    avahi_threaded_poll_free(poll_);
    poll_ = nullptr;
  }
}

AvahiPublisher::~AvahiPublisher() {
  if (poll_ == nullptr) return;
  avahi_threaded_poll_stop(poll_);                     // the thread is gone: callbacks are over
  if (client_ != nullptr) avahi_client_free(client_);  // frees the group too
  if (retry_ != nullptr) avahi_threaded_poll_get(poll_)->timeout_free(retry_);
  avahi_threaded_poll_free(poll_);
}

void AvahiPublisher::connect() {
  int error = 0;
  // NO_FAIL: without avahi-daemon the client waits for it (state
  // CONNECTING) instead of failing, so a daemon started later is used.
  client_ = avahi_client_new(avahi_threaded_poll_get(poll_), AVAHI_CLIENT_NO_FAIL,
                             &AvahiCallbacks::client, this, &error);
  if (client_ != nullptr) return;
  // No D-Bus system bus at all (NO_FAIL waits for avahi-daemon, not for
  // D-Bus): try again later, from Avahi's thread.
  if (!absence_reported_) {
    log::info("avahi: avahi-daemon is not reachable (%s); rotord is announced when it is",
              avahi_strerror(error));
    absence_reported_ = true;
  }
  const AvahiPoll* api = avahi_threaded_poll_get(poll_);
  timeval when{};
  avahi_elapse_time(&when, kRetryMs, 0);
  if (retry_ == nullptr) {
    retry_ = api->timeout_new(api, &when, &AvahiCallbacks::retry, this);
  } else {
    api->timeout_update(retry_, &when);
  }
}

void AvahiPublisher::on_client(AvahiClient* client, int state) {
  switch (static_cast<AvahiClientState>(state)) {
    case AVAHI_CLIENT_S_RUNNING:
      absence_reported_ = false;
      if (retry_ != nullptr) avahi_threaded_poll_get(poll_)->timeout_update(retry_, nullptr);
      register_services(client);
      break;
    case AVAHI_CLIENT_S_COLLISION:
    case AVAHI_CLIENT_S_REGISTERING:
      // The host name changes or collides: withdraw, re-announce when running.
      if (group_ != nullptr) avahi_entry_group_reset(group_);
      break;
    case AVAHI_CLIENT_CONNECTING:
      if (!absence_reported_) {
        log::info("avahi: avahi-daemon is not running; rotord is announced when it starts");
        absence_reported_ = true;
      }
      break;
    case AVAHI_CLIENT_FAILURE:
      if (avahi_client_errno(client) == AVAHI_ERR_DISCONNECTED) {
        // avahi-daemon went away (restarted): a new client waits for it.
        log::info("avahi: avahi-daemon went away; rotord is announced again when it is back");
        absence_reported_ = true;
        avahi_client_free(client);
        client_ = nullptr;
        group_ = nullptr;
        connect();
      } else {
        log::warn("avahi: %s; rotord is not announced on the network",
                  avahi_strerror(avahi_client_errno(client)));
      }
      break;
  }
}

void AvahiPublisher::register_services(AvahiClient* client) {
  if (name_.empty()) name_ = std::string("rotord on ") + avahi_client_get_host_name(client);
  if (group_ == nullptr) {
    group_ = avahi_entry_group_new(client, &AvahiCallbacks::group, this);
    if (group_ == nullptr) {
      log::warn("avahi: %s", avahi_strerror(avahi_client_errno(client)));
      return;
    }
  }
  if (!avahi_entry_group_is_empty(group_)) return;  // registered already
  int error = AVAHI_OK;
  if (ports_.web != 0) {
    error = avahi_entry_group_add_service(group_, AVAHI_IF_UNSPEC, AVAHI_PROTO_UNSPEC,
                                          AvahiPublishFlags{}, name_.c_str(), net::kHttpServiceType,
                                          nullptr, nullptr, ports_.web, net::kHttpTxt,
                                          static_cast<const char*>(nullptr));
  }
  if (error == AVAHI_OK && ports_.rotctld != 0) {
    const net::RotctldTxt txt(ports_, version_.c_str());
    AvahiStringList* list = nullptr;
    for (std::size_t n = txt.size(); n-- > 0;) list = avahi_string_list_add(list, txt[n]);
    error = avahi_entry_group_add_service_strlst(
        group_, AVAHI_IF_UNSPEC, AVAHI_PROTO_UNSPEC, AvahiPublishFlags{}, name_.c_str(),
        net::kRotctldServiceType, nullptr, nullptr, ports_.rotctld, list);
    avahi_string_list_free(list);
  }
  if (error == AVAHI_ERR_COLLISION) {
    // Another service of that name on the network: "rotord on pi #2".
    char* other = avahi_alternative_service_name(name_.c_str());
    name_ = other;
    avahi_free(other);
    avahi_entry_group_reset(group_);
    register_services(client);
    return;
  }
  if (error == AVAHI_OK) error = avahi_entry_group_commit(group_);
  if (error != AVAHI_OK) log::warn("avahi: cannot announce rotord: %s", avahi_strerror(error));
}

void AvahiPublisher::on_group(AvahiEntryGroup* group, int state) {
  switch (static_cast<AvahiEntryGroupState>(state)) {
    case AVAHI_ENTRY_GROUP_ESTABLISHED:
      log::info("avahi: announced as '%s' (%s port %u, %s port %u)", name_.c_str(),
                net::kHttpServiceType, static_cast<unsigned>(ports_.web), net::kRotctldServiceType,
                static_cast<unsigned>(ports_.rotctld));
      break;
    case AVAHI_ENTRY_GROUP_COLLISION: {
      char* other = avahi_alternative_service_name(name_.c_str());
      log::info("avahi: the name '%s' is taken on the network; trying '%s'", name_.c_str(), other);
      name_ = other;
      avahi_free(other);
      avahi_entry_group_reset(group);
      register_services(avahi_entry_group_get_client(group));
      break;
    }
    case AVAHI_ENTRY_GROUP_FAILURE:
      log::warn("avahi: announcing failed: %s",
                avahi_strerror(avahi_client_errno(avahi_entry_group_get_client(group))));
      break;
    case AVAHI_ENTRY_GROUP_UNCOMMITED:
    case AVAHI_ENTRY_GROUP_REGISTERING:
      break;
  }
}

}  // namespace rotord::linux_port
