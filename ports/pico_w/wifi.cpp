#include "wifi.hpp"

#include <cstdio>
#include <cstring>

#include "lwip/apps/mdns.h"
#include "lwip/ip4_addr.h"
#include "lwip/netif.h"
#include "pico/cyw43_arch.h"

namespace rotord::pico_w {

namespace {

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

void Wifi::begin(Millis now) {
  mdns_resp_init();
  if (config_.ssid[0] == '\0') {
    std::printf("rotord: no Wi-Fi network configured (ROTORD_WIFI_SSID)\n");
    start_access_point();
    return;
  }
  cyw43_arch_enable_sta_mode();
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
  if (state_ != State::kJoining && state_ != State::kStation) return;
  const int status = cyw43_tcpip_link_status(&cyw43_state, CYW43_ITF_STA);
  if (status != last_status_) {
    std::printf("rotord: Wi-Fi %s\n", link_status_name(status));
    last_status_ = status;
  }
  if (state_ == State::kJoining) {
    if (status == CYW43_LINK_UP) {
      state_ = State::kStation;
      log_address("station", CYW43_ITF_STA);
      announce(CYW43_ITF_STA);
      return;
    }
    // A wrong password will not fix itself; a missing network might, but
    // the user needs a way in meanwhile: both end in the setup AP.
    const bool failed =
        status == CYW43_LINK_BADAUTH || status == CYW43_LINK_FAIL || status == CYW43_LINK_NONET;
    if (failed || now - join_started_ >= config_.join_timeout_ms) {
      std::printf("rotord: Wi-Fi station did not come up (%s)\n", link_status_name(status));
      cyw43_arch_disable_sta_mode();
      start_access_point();
    }
    return;
  }
  // Station was up and the link dropped (router restart): join again, which
  // falls back to the AP if the network stays away.
  if (status != CYW43_LINK_UP && status != CYW43_LINK_NOIP && status != CYW43_LINK_JOIN) {
    start_join(now);
  }
}

void Wifi::start_access_point() {
  const bool open = std::strlen(config_.ap_password) < 8;  // WPA2 needs 8..63
  cyw43_arch_enable_ap_mode(kApSsid, open ? nullptr : config_.ap_password,
                            open ? CYW43_AUTH_OPEN : CYW43_AUTH_WPA2_AES_PSK);
  state_ = State::kAccessPoint;
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
  if (mdns_resp_add_netif(n, kMdnsName) != ERR_OK) {
    std::printf("rotord: mDNS not available on this interface\n");
    return;
  }
  mdns_resp_add_service(n, kMdnsName, "_http", DNSSD_PROTO_TCP, kHttpPort, nullptr, nullptr);
  mdns_on_[itf] = true;
  std::printf("rotord: mDNS name %s.local\n", kMdnsName);
}

void Wifi::log_address(const char* what, int itf) {
  const netif& n = cyw43_state.netif[itf];
  char text[IP4ADDR_STRLEN_MAX];
  ip4addr_ntoa_r(netif_ip4_addr(&n), text, sizeof(text));
  std::printf("rotord: %s address %s\n", what, text);
}

}  // namespace rotord::pico_w
