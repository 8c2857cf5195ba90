#pragma once
// The list settings of access control: host names (web.allowed_hosts) and
// IPv4 and IPv6 networks (access.control_networks), items separated by
// commas or spaces. Parsed where they are used, per request, so a change applies at
// once and no parsed copy has to be kept in step.
#include <cstdint>

#include <string_view>
#include "access/peer.hpp"

#include "util/slice.hpp"

namespace rotord::settings {

/// Calls `each(item)` for every non-empty item of a comma- or space-separated list.
template <typename Each>
void for_each_list_item(std::string_view list, Each&& each) {
  while (!list.empty()) {
    const std::size_t end = list.find_first_of(", ");
    const std::string_view item = text::slice(list, 0, end);
    if (!item.empty()) each(item);
    if (end == std::string_view::npos) break;
    list.remove_prefix(end + 1);
  }
}

/// An IPv4 network, address and mask in host order.
struct Ipv4Network {
  std::uint32_t address = 0;
  std::uint32_t mask = 0;
  bool contains(std::uint32_t ipv4) const { return (ipv4 & mask) == (address & mask); }
};

/// "192.168.1.0/24" or "10.0.0.5" (a /32). Host bits may be set ("10.0.0.5/8"
/// is 10.0.0.0/8), as the address a user knows is often their own.
bool parse_ipv4_network(std::string_view text, Ipv4Network& out);

/// "2001:db8::1", "::1", "::ffff:10.0.0.1" (RFC 4291 2.2): groups of one to
/// four hex digits, one "::" at most, an IPv4 address as the last 32 bits.
/// No zone ("fe80::1%eth0"): a zone names an interface of one host, which an
/// allow-list shared by every interface cannot mean. Hand-written: the core
/// runs on the Pico, where no inet_pton is at hand.
bool parse_ipv6(std::string_view text, access::IpBytes& out);

/// An IPv4 or IPv6 network: IPv4 is held as its IPv4-mapped IPv6 network
/// (10.0.0.0/8 as ::ffff:10.0.0.0/104), so an IPv4 client matches it whether
/// it came over IPv4 or as ::ffff:a.b.c.d on a dual-stack socket.
struct IpNetwork {
  access::IpBytes address{};
  unsigned prefix_bits = 0;  ///< 0-128
  bool contains(const access::IpBytes& a) const;
};

/// "192.168.1.0/24", "10.0.0.5" (a /32), "fd00::/8", "2001:db8::/32",
/// "::1" (a /128). Host bits may be set, as for IPv4.
bool parse_network(std::string_view text, IpNetwork& out);

/// Whether `ipv4` (host order) is in one of the list's networks.
bool in_network_list(std::string_view list, std::uint32_t ipv4);
/// Whether a network client is in one of the list's networks (false for
/// anything that is not an IPv4 or IPv6 client).
bool in_network_list(std::string_view list, const access::Peer& peer);

/// RFC 1123 host name: labels of letters, digits and '-' joined by dots (a
/// dotted quad passes too). A trailing dot is not accepted.
bool is_hostname(std::string_view name);

}  // namespace rotord::settings
