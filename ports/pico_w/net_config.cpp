#include "net_config.hpp"

extern "C" {
#include "lwip/def.h"
#include "lwip/ip4_addr.h"
#include "lwip/netif.h"
}

namespace rotord::pico_w {

using settings::Id;

std::optional<StaticIpv4> static_ipv4_from(const settings::Settings& s) {
  if (s.i(Id::kNetIpv4Mode) != 1) return std::nullopt;
  StaticIpv4 c;
  if (!settings::parse_ipv4(s.text(Id::kNetIpv4Address), c.address) ||
      !settings::parse_ipv4(s.text(Id::kNetIpv4Netmask), c.netmask))
    return std::nullopt;
  if (!settings::parse_ipv4(s.text(Id::kNetIpv4Gateway), c.gateway)) c.gateway = 0;
  if (!settings::parse_ipv4(s.text(Id::kNetIpv4Dns), c.dns)) c.dns = c.gateway;
  return c;
}

void apply_static_ipv4(netif& n, const StaticIpv4& config) {
  ip4_addr_t address;
  ip4_addr_t netmask;
  ip4_addr_t gateway;
  // ip4_addr_t holds network order.
  ip4_addr_set_u32(&address, lwip_htonl(config.address));
  ip4_addr_set_u32(&netmask, lwip_htonl(config.netmask));
  ip4_addr_set_u32(&gateway, lwip_htonl(config.gateway));
  netif_set_addr(&n, &address, &netmask, &gateway);
}

}  // namespace rotord::pico_w
