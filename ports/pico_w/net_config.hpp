#pragma once
// The Pico W's network settings (the Network group of the settings table)
// turned into what lwIP and the cyw43 driver take. Pure lwIP, no SDK: the
// host tests (tests/lwip) apply a static address to a netif of Debian's lwIP.
#include <cstdint>
#include <optional>

#include "settings/settings.hpp"

struct netif;

namespace rotord::pico_w {

/// A fixed IPv4 configuration, addresses in host order (192.168.1.20 =
/// 0xC0A80114). gateway and dns are 0 when not given.
struct StaticIpv4 {
  std::uint32_t address = 0;
  std::uint32_t netmask = 0;
  std::uint32_t gateway = 0;
  std::uint32_t dns = 0;  ///< net.ipv4_dns, else the gateway
};

/// The static configuration when net.ipv4_mode = static and the addresses
/// parse (check_consistency has refused anything else); nullopt for DHCP.
std::optional<StaticIpv4> static_ipv4_from(const settings::Settings& s);

/// Sets the netif's address, netmask and gateway (netif_set_addr). The caller
/// stops the DHCP client first (the cyw43 driver starts one on the station)
/// and sets the DNS server; Debian's host lwIP has neither compiled in.
void apply_static_ipv4(netif& n, const StaticIpv4& config);

}  // namespace rotord::pico_w
