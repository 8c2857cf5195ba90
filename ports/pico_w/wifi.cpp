#include "wifi.hpp"

#include <cstdio>
#include <cstring>

#include "lwip/apps/mdns.h"
#include "lwip/apps/sntp.h"
#include "lwip/dhcp.h"
#include "lwip/dns.h"
#include "lwip/ip4_addr.h"
#include "lwip/netif.h"
#include "pico/cyw43_arch.h"
#include "pico/time.h"
#include "sntp_clock.hpp"

// lwIP's SNTP client reports the time here (SNTP_SET_SYSTEM_TIME_US in
// config/lwipopts.h), from the poll loop's context.
extern "C" void rotord_sntp_set_time_us(std::uint32_t sec, std::uint32_t us) {
  rotord::pico_w::on_sntp_time(sec, us,
                               static_cast<rotord::Millis>(to_ms_since_boot(get_absolute_time())));
  std::printf("rotord: time set by SNTP (%lu s since 1970)\n", static_cast<unsigned long>(sec));
}

namespace rotord::pico_w {

namespace {

template <std::size_t N>
void copy_text(char (&out)[N], std::string_view text) {
  const std::size_t n = text.size() < N - 1 ? text.size() : N - 1;
  if (n > 0) std::memcpy(out, text.data(), n);  // an empty view's data() may be null
  out[n] = '\0';
}

const char* link_status_name(int status) {
  switch (status) {
    case CYW43_LINK_DOWN:
      return "down";
    case CYW43_LINK_JOIN:
      return "joined";
    case CYW43_LINK_NOIP:
      return "waiting for DHCP";
    case CYW43_LINK_UP:
      return "up";
    case CYW43_LINK_FAIL:
      return "failed";
    case CYW43_LINK_NONET:
      return "network not found";
    case CYW43_LINK_BADAUTH:
      return "wrong password";
    default:
      return "unknown";
  }
}

}  // namespace

Wifi::Config Wifi::config_from(const settings::Settings& s, Millis join_timeout_ms) {
  using settings::Id;
  Config c;
  copy_text(c.ssid, s.text(Id::kWifiSsid));
  copy_text(c.password, s.text(Id::kWifiPassword));
  copy_text(c.ap_password, s.text(Id::kWifiApPassword));
  c.ap_policy.has_password = std::strlen(c.ap_password) >= 8;  // WPA2 needs 8..63
  c.ap_policy.open_minutes = s.i(Id::kWifiApOpenMinutes);
  copy_text(c.hostname, s.text(Id::kNetHostname));
  c.static_ipv4 = static_ipv4_from(s);
  c.sntp = s.b(Id::kTimeSntpEnabled) && !s.text(Id::kTimeSntpServer).empty();
  copy_text(c.sntp_server, s.text(Id::kTimeSntpServer));
  c.join_timeout_ms = join_timeout_ms;
  return c;
}

void Wifi::begin(Millis now) {
  mdns_resp_init();
  if (config_.ssid[0] == '\0') {
    std::printf("rotord: no Wi-Fi network configured (wifi.ssid)\n");
    start_access_point(now);
    return;
  }
  start_station(now);
}

void Wifi::start_station(Millis now) {
  cyw43_arch_enable_sta_mode();  // adds the station netif and starts its DHCP client
  netif* sta = &cyw43_state.netif[CYW43_ITF_STA];
  if (config_.hostname[0] != '\0') netif_set_hostname(sta, config_.hostname);
  if (config_.static_ipv4) {
    // Before the link is up, so no DHCP request ever goes out.
    dhcp_stop(sta);
    apply_static_ipv4(*sta, *config_.static_ipv4);
    if (config_.static_ipv4->dns != 0) {
      ip_addr_t dns;
      ip_addr_set_ip4_u32(&dns, lwip_htonl(config_.static_ipv4->dns));
      dns_setserver(0, &dns);
    }
    log_address("static", CYW43_ITF_STA);
  }
  start_join(now);
}

void Wifi::start_join(Millis now) {
  const bool open = config_.password[0] == '\0';
  const int err = cyw43_arch_wifi_connect_async(config_.ssid, open ? nullptr : config_.password,
                                                open ? CYW43_AUTH_OPEN : CYW43_AUTH_WPA2_AES_PSK);
  std::printf("rotord: joining Wi-Fi '%s'%s\n", config_.ssid, err != 0 ? " failed to start" : "");
  state_ = State::kJoining;
  join_started_ = now;
  last_status_ = CYW43_LINK_DOWN;
}

void Wifi::step(Millis now) {
  if (state_ == State::kAccessPoint) {
    if (setup_ap_closed(now)) return;
    retry_station_from_access_point(now);
    return;
  }
  if (state_ == State::kOff) {
    // The open AP's window is over: only the configured network remains.
    if (config_.ssid[0] != '\0' && now - ap_started_ >= kApRetryMs) {
      ap_started_ = now;
      start_station(now);
    }
    return;
  }
  if (state_ != State::kJoining && state_ != State::kStation) return;
  const int status = cyw43_tcpip_link_status(&cyw43_state, CYW43_ITF_STA);
  if (status != last_status_) {
    std::printf("rotord: Wi-Fi %s\n", link_status_name(status));
    last_status_ = status;
  }
  if (state_ == State::kJoining) {
    if (status == CYW43_LINK_UP) {
      station_up();
      return;
    }
    // A wrong password will not fix itself; a missing network might, but
    // the user needs a way in meanwhile: both end in the setup AP.
    const bool failed =
        status == CYW43_LINK_BADAUTH || status == CYW43_LINK_FAIL || status == CYW43_LINK_NONET;
    if (failed || now - join_started_ >= config_.join_timeout_ms) {
      std::printf("rotord: Wi-Fi station did not come up (%s)\n", link_status_name(status));
      if (mdns_on_[CYW43_ITF_STA]) {  // the netif goes; a later join adds it anew
        mdns_resp_remove_netif(&cyw43_state.netif[CYW43_ITF_STA]);
        mdns_on_[CYW43_ITF_STA] = false;
      }
      cyw43_arch_disable_sta_mode();
      start_access_point(now);
    }
    return;
  }
  // Station was up and the link dropped (router restart): join again, which
  // falls back to the AP if the network stays away.
  if (status != CYW43_LINK_UP && status != CYW43_LINK_NOIP && status != CYW43_LINK_JOIN) {
    start_join(now);
  }
}

void Wifi::station_up() {
  state_ = State::kStation;
  log_address("station", CYW43_ITF_STA);
  announce(CYW43_ITF_STA);
  if (config_.sntp && !sntp_started_) {
    // Polls the server (a name goes through DNS) now and every hour after.
    sntp_setoperatingmode(SNTP_OPMODE_POLL);
    sntp_setservername(0, config_.sntp_server);
    sntp_init();
    sntp_started_ = true;
    std::printf("rotord: SNTP from %s\n", config_.sntp_server);
  }
}

void Wifi::retry_station_from_access_point(Millis now) {
  if (config_.ssid[0] == '\0' || now - ap_started_ < kApRetryMs) return;
  int stations = 0;
  cyw43_wifi_ap_get_stas(&cyw43_state, &stations, nullptr);
  if (stations > 0) {
    ap_started_ = now;  // someone is using the setup AP: ask again later
    return;
  }
  std::printf("rotord: nobody on the access point; trying Wi-Fi '%s' again\n", config_.ssid);
  dhcp_.stop();
  if (mdns_on_[CYW43_ITF_AP]) {
    mdns_resp_remove_netif(&cyw43_state.netif[CYW43_ITF_AP]);
    mdns_on_[CYW43_ITF_AP] = false;
  }
  cyw43_arch_disable_ap_mode();
  start_station(now);  // falls back to the AP again after the join timeout
}

bool Wifi::setup_ap_closed(Millis now) {
  // Milliseconds since boot: the loop's clock starts at power-on.
  int stations = 0;
  if (state_ == State::kAccessPoint) cyw43_wifi_ap_get_stas(&cyw43_state, &stations, nullptr);
  if (config_.ap_policy.may_offer(now, stations)) return false;
  if (!ap_window_over_logged_) {
    std::printf(
        "rotord: the open access point '%s' is offered only %d min after power-on "
        "(wifi.ap_open_minutes); power-cycle to open it again, or set wifi.ap_password\n",
        kApSsid, config_.ap_policy.open_minutes);
    ap_window_over_logged_ = true;
  }
  if (state_ == State::kAccessPoint) {
    dhcp_.stop();
    if (mdns_on_[CYW43_ITF_AP]) {
      mdns_resp_remove_netif(&cyw43_state.netif[CYW43_ITF_AP]);
      mdns_on_[CYW43_ITF_AP] = false;
    }
    cyw43_arch_disable_ap_mode();
  }
  state_ = State::kOff;
  ap_started_ = now;  // the configured network is tried again every kApRetryMs
  return true;
}

void Wifi::start_access_point(Millis now) {
  if (setup_ap_closed(now)) return;
  const bool open = std::strlen(config_.ap_password) < 8;  // WPA2 needs 8..63
  cyw43_arch_enable_ap_mode(kApSsid, open ? nullptr : config_.ap_password,
                            open ? CYW43_AUTH_OPEN : CYW43_AUTH_WPA2_AES_PSK);
  state_ = State::kAccessPoint;
  ap_started_ = now;
  std::printf("rotord: access point '%s' (%s)\n", kApSsid, open ? "open" : "WPA2");
  log_address("access point", CYW43_ITF_AP);
  announce(CYW43_ITF_AP);
  if (!dhcp_.start(&cyw43_state.netif[CYW43_ITF_AP]))
    std::printf("rotord: DHCP server did not start; clients need a fixed 192.168.4.x address\n");
}

void Wifi::announce(int itf) {
  netif* n = &cyw43_state.netif[itf];
  if (mdns_on_[itf]) {
    mdns_resp_announce(n);  // a new address after a re-join
    return;
  }
  if (config_.hostname[0] == '\0') return;  // net.hostname empty: no mDNS
  if (mdns_resp_add_netif(n, config_.hostname) != ERR_OK) {
    std::printf("rotord: mDNS not available on this interface\n");
    return;
  }
  mdns_resp_add_service(n, config_.hostname, net::kHttpService, DNSSD_PROTO_TCP, config_.ports.web,
                        &Wifi::http_txt, this);
  if (config_.ports.rotctld != 0)
    mdns_resp_add_service(n, config_.hostname, net::kRotctldService, DNSSD_PROTO_TCP,
                          config_.ports.rotctld, &Wifi::rotctld_txt, this);
  mdns_on_[itf] = true;
  std::printf("rotord: mDNS name %s.local\n", config_.hostname);
}

void Wifi::http_txt(mdns_service* service, void*) {
  mdns_resp_add_service_txtitem(service, net::kHttpTxt,
                                static_cast<u8_t>(std::strlen(net::kHttpTxt)));
}

void Wifi::rotctld_txt(mdns_service* service, void* self) {
  // The same records as Linux's Avahi announcement (core/net/dns_sd.hpp).
  const net::RotctldTxt txt(static_cast<const Wifi*>(self)->config_.ports, ROTORD_VERSION);
  for (std::size_t n = 0; n < txt.size(); ++n)
    mdns_resp_add_service_txtitem(service, txt[n], static_cast<u8_t>(std::strlen(txt[n])));
}

void Wifi::log_address(const char* what, int itf) {
  const netif& n = cyw43_state.netif[itf];
  char text[IP4ADDR_STRLEN_MAX];
  ip4addr_ntoa_r(netif_ip4_addr(&n), text, sizeof(text));
  std::printf("rotord: %s address %s\n", what, text);
}

}  // namespace rotord::pico_w
