#pragma once
// Wi-Fi bring-up for the Pico W: join the configured network as a station;
// when there is no network configured, or it cannot be joined within the
// timeout, open the access point `rotord-setup` (192.168.4.1, with a small
// DHCP server) instead. Stepped from the main loop like everything else.
// The AP stays until the next boot: station retries while the AP runs are
// not implemented.
#include <cstdint>

#include "dhcp_server.hpp"
#include "util/time.hpp"

namespace rotord::pico_w {

class Wifi {
 public:
  enum class State : std::uint8_t { kOff, kJoining, kStation, kAccessPoint };

  static constexpr const char* kApSsid = "rotord-setup";
  /// mDNS host name: the web UI is at http://rotord.local/ on either network.
  static constexpr const char* kMdnsName = "rotord";
  static constexpr std::uint16_t kHttpPort = 80;

  struct Config {
    const char* ssid = "";
    const char* password = "";     ///< empty: open network
    const char* ap_password = "";  ///< empty or < 8 characters: open AP
    Millis join_timeout_ms = 30'000;
  };

  explicit Wifi(const Config& config) : config_(config) {}
  /// cyw43_arch_init() must have succeeded.
  void begin(Millis now);
  void step(Millis now);
  State state() const { return state_; }

 private:
  void start_join(Millis now);
  void start_access_point();
  static void log_address(const char* what, int itf);
  void announce(int itf);

  Config config_;
  lwip_port::DhcpServer dhcp_;  ///< hands out addresses on the setup AP
  State state_ = State::kOff;
  Millis join_started_ = 0;
  int last_status_ = 0;
  bool mdns_on_[2] = {false, false};  ///< per cyw43 interface (STA, AP)
};

}  // namespace rotord::pico_w
