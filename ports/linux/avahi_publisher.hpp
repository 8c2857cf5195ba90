#pragma once
// Announces rotord on the local network through avahi-daemon (Avahi's
// client library, Debian libavahi-client-dev): the web UI as _http._tcp and
// Hamlib rotctld as _rotctld._tcp with the other protocols' ports as TXT
// records (core/net/dns_sd.hpp, the Pico W announces the same). Avahi's own
// thread (AvahiThreadedPoll) talks to the daemon over D-Bus, so the control
// loop never waits on it; it touches nothing of the daemon but the log.
// Without avahi-daemon (or D-Bus) rotord runs as before and says so once; a
// daemon that starts or restarts later is found and used (AVAHI_CLIENT_NO_FAIL;
// without D-Bus itself, a new try every kRetryMs).
#include <string>

#include "net/dns_sd.hpp"

struct AvahiThreadedPoll;
struct AvahiClient;
struct AvahiEntryGroup;
struct AvahiTimeout;

namespace rotord::linux_port {

class AvahiPublisher {
 public:
  /// Without D-Bus (the client cannot even wait for avahi-daemon): next try.
  static constexpr unsigned kRetryMs = 30'000;

  /// Starts the announcing thread. `ports`: 0 for a protocol that is off.
  AvahiPublisher(const net::ServicePorts& ports, std::string version);
  /// Withdraws the services and stops the thread.
  ~AvahiPublisher();
  AvahiPublisher(const AvahiPublisher&) = delete;
  AvahiPublisher& operator=(const AvahiPublisher&) = delete;

 private:
  friend struct AvahiCallbacks;  // Avahi's callbacks, with its enum types
  void on_client(AvahiClient* client, int state);
  void on_group(AvahiEntryGroup* group, int state);
  /// Connects a new client (again after avahi-daemon went away).
  void connect();
  void register_services(AvahiClient* client);

  net::ServicePorts ports_;
  std::string version_;
  std::string name_;  ///< "rotord on <host>", or Avahi's alternative after a collision
  AvahiThreadedPoll* poll_ = nullptr;
  AvahiClient* client_ = nullptr;
  AvahiEntryGroup* group_ = nullptr;
  AvahiTimeout* retry_ = nullptr;
  bool absence_reported_ = false;
};

}  // namespace rotord::linux_port
