#pragma once
// Wi-Fi bring-up for the Pico W, from the Network settings: join wifi.ssid as
// a station (DHCP, or the fixed net.ipv4_* address); when no network is
// configured, or it cannot be joined within the timeout, open the access
// point `rotord-setup` (192.168.4.1, with a small DHCP server) instead, where
// the web settings page takes the network's name and password (then POST
// /api/reboot). mDNS answers for net.hostname.local on either network; once
// the station is up, SNTP sets the calendar time (sntp_clock.hpp). Stepped
// from the main loop like everything else. When a network is configured but
// the AP had to open (the router was still booting after a power cut, a
// password changed), the AP tries the network again every kApRetryMs while
// no phone is connected to it, so the controller comes back on its own.
#include <cstdint>
#include <optional>

#include "dhcp_server.hpp"
#include "net/dns_sd.hpp"
#include "net/setup_ap.hpp"
#include "net_config.hpp"
#include "settings/settings.hpp"
#include "util/time.hpp"

struct mdns_service;

namespace rotord::pico_w {

class Wifi {
 public:
  enum class State : std::uint8_t { kOff, kJoining, kStation, kAccessPoint };

  static constexpr const char* kApSsid = "rotord-setup";
  static constexpr std::uint16_t kHttpPort = 80;
  /// How long the setup AP stays before the configured network is tried
  /// again (only while nobody is connected to the AP: a retry takes the AP
  /// down for up to the join timeout).
  static constexpr Millis kApRetryMs = 5 * 60'000;

  /// Copies of the settings (they may change at run time; the network takes
  /// them at boot, as their restart flag says).
  struct Config {
    char ssid[33] = "";            ///< empty: start the setup access point
    char password[64] = "";        ///< empty: open network
    char ap_password[64] = "";     ///< empty (or under 8 characters): open AP
    net::SetupApPolicy ap_policy;  ///< how long an open AP may be offered
    char hostname[33] = "";        ///< mDNS and DHCP name; empty: no mDNS
    std::optional<StaticIpv4> static_ipv4;
    bool sntp = false;
    char sntp_server[64] = "";
    Millis join_timeout_ms = 30'000;
    /// Announced by mDNS (core/net/dns_sd.hpp): the web UI as _http._tcp,
    /// rotctld as _rotctld._tcp with the other ports as TXT records.
    net::ServicePorts ports{kHttpPort};
  };
  static Config config_from(const settings::Settings& s, Millis join_timeout_ms);

  explicit Wifi(const Config& config) : config_(config) {}
  /// cyw43_arch_init() must have succeeded.
  void begin(Millis now);
  void step(Millis now);
  State state() const { return state_; }

 private:
  void start_station(Millis now);
  void start_join(Millis now);
  void start_access_point(Millis now);
  void retry_station_from_access_point(Millis now);
  /// The open AP's window has passed: closes it (or does not open it) and
  /// keeps trying the configured network, if there is one.
  bool setup_ap_closed(Millis now);
  void station_up();
  static void log_address(const char* what, int itf);
  void announce(int itf);
  /// lwIP's TXT callbacks (service_get_txt_fn_t).
  static void http_txt(mdns_service* service, void* self);
  static void rotctld_txt(mdns_service* service, void* self);

  Config config_;
  lwip_port::DhcpServer dhcp_;  ///< hands out addresses on the setup AP
  State state_ = State::kOff;
  Millis join_started_ = 0;
  Millis ap_started_ = 0;
  int last_status_ = 0;
  bool mdns_on_[2] = {false, false};  ///< per cyw43 interface (STA, AP)
  bool sntp_started_ = false;
  bool ap_window_over_logged_ = false;
};

}  // namespace rotord::pico_w
