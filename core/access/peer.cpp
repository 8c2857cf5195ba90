#include "access/peer.hpp"

#include <cstdio>

namespace rotord::access {
namespace {

bool is_v4_mapped(const IpBytes& a) {
  for (std::size_t i = 0; i < 10; ++i)
    if (a[i] != 0) return false;
  return a[10] == 0xFF && a[11] == 0xFF;
}

}  // namespace

Peer Peer::from_ipv6(const IpBytes& address) {
  if (is_v4_mapped(address)) {
    return from_ipv4((std::uint32_t{address[12]} << 24) | (std::uint32_t{address[13]} << 16) |
                     (std::uint32_t{address[14]} << 8) | address[15]);
  }
  Peer p;
  p.kind = Kind::kIpv6;
  p.ipv6 = address;
  return p;
}

IpBytes Peer::address() const {
  IpBytes a{};
  if (kind == Kind::kIpv6) return ipv6;
  if (kind == Kind::kIpv4) {
    a[10] = 0xFF;
    a[11] = 0xFF;
    a[12] = static_cast<std::uint8_t>(ipv4 >> 24);
    a[13] = static_cast<std::uint8_t>(ipv4 >> 16);
    a[14] = static_cast<std::uint8_t>(ipv4 >> 8);
    a[15] = static_cast<std::uint8_t>(ipv4);
  }
  return a;
}

IpBytes Peer::host_key() const {
  IpBytes a = address();
  if (kind == Kind::kIpv6) {
    for (std::size_t i = 8; i < a.size(); ++i) a[i] = 0;
  }
  return a;
}

std::uint32_t Peer::address_hash() const {
  if (kind != Kind::kIpv6) return ipv4;
  std::uint32_t h = 2166136261u;
  for (const std::uint8_t b : ipv6) h = (h ^ b) * 16777619u;
  return h;
}

bool Peer::same_host(const Peer& other) const {
  return kind == other.kind && (!is_network() || host_key() == other.host_key());
}

const char* address_text(const IpBytes& a, char (&out)[kAddressTextBytes]) {
  if (is_v4_mapped(a)) {
    std::snprintf(out, sizeof out, "::ffff:%u.%u.%u.%u", a[12], a[13], a[14], a[15]);
    return out;
  }
  unsigned groups[8];
  for (std::size_t g = 0; g < 8; ++g) groups[g] = (unsigned{a[2 * g]} << 8) | a[2 * g + 1];
  // RFC 5952 4.2: the longest run of two or more zero groups (the first of
  // equal ones) becomes "::".
  int best_at = -1;
  int best_len = 1;
  for (int g = 0; g < 8;) {
    if (groups[g] != 0) {
      ++g;
      continue;
    }
    int end = g;
    while (end < 8 && groups[end] == 0) ++end;
    if (end - g > best_len) {
      best_at = g;
      best_len = end - g;
    }
    g = end;
  }
  std::size_t n = 0;
  for (int g = 0; g < 8; ++g) {
    if (g == best_at) {
      n += static_cast<std::size_t>(std::snprintf(out + n, sizeof out - n, "::"));
      g += best_len - 1;
      continue;
    }
    const bool after_gap = best_at >= 0 && g == best_at + best_len;
    n += static_cast<std::size_t>(
        std::snprintf(out + n, sizeof out - n, "%s%x", g == 0 || after_gap ? "" : ":", groups[g]));
  }
  return out;
}

const char* peer_text(const Peer& peer, char (&out)[kAddressTextBytes], bool host) {
  switch (peer.kind) {
    case Peer::Kind::kIpv4:
      std::snprintf(out, sizeof out, "%u.%u.%u.%u", static_cast<unsigned>(peer.ipv4 >> 24),
                    static_cast<unsigned>(peer.ipv4 >> 16 & 0xff),
                    static_cast<unsigned>(peer.ipv4 >> 8 & 0xff),
                    static_cast<unsigned>(peer.ipv4 & 0xff));
      return out;
    case Peer::Kind::kIpv6:
      return address_text(host ? peer.host_key() : peer.ipv6, out);
    case Peer::Kind::kOther:
      return "a network client";
    case Peer::Kind::kLine:
      return "a serial port";
    case Peer::Kind::kUnknown:
      break;
  }
  return "an unknown client";
}

}  // namespace rotord::access
