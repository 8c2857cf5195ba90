#pragma once
// asio addresses to and from the core's access::Peer: one place that knows
// an IPv4 client of a dual-stack socket (::ffff:a.b.c.d) is an IPv4 client.
#include <asio.hpp>

#include "access/peer.hpp"

namespace rotord::linux_port {

inline access::Peer peer_of(const asio::ip::address& address) {
  if (address.is_v4()) return access::Peer::from_ipv4(address.to_v4().to_uint());
  const asio::ip::address_v6::bytes_type bytes = address.to_v6().to_bytes();
  access::IpBytes ip{};
  for (std::size_t i = 0; i < ip.size(); ++i) ip[i] = bytes[i];
  return access::Peer::from_ipv6(ip);  // v4-mapped comes back as IPv4
}

/// For the logs: an IPv4 client of a dual-stack socket as the IPv4 address
/// it is ("192.0.2.7", not "::ffff:192.0.2.7").
inline asio::ip::address unmapped(const asio::ip::address& address) {
  if (address.is_v6() && address.to_v6().is_v4_mapped())
    return asio::ip::make_address_v4(asio::ip::v4_mapped, address.to_v6());
  return address;
}

/// Where to send to `peer` from a socket of `family`: an IPv4 peer of an
/// IPv6 socket is reached at its v4-mapped address. Unspecified for a peer
/// that is not a network client.
inline asio::ip::address address_of(const access::Peer& peer, bool v6_socket) {
  if (peer.kind == access::Peer::Kind::kIpv6 || (v6_socket && peer.is_network())) {
    const access::IpBytes ip = peer.address();
    asio::ip::address_v6::bytes_type bytes{};
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = ip[i];
    return asio::ip::address_v6(bytes);
  }
  return asio::ip::address_v4(peer.ipv4);
}

}  // namespace rotord::linux_port
