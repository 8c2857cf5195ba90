#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

namespace rotord::access {

/// An IP address in 16 bytes, network order: IPv6 as it is, IPv4 as
/// ::ffff:a.b.c.d (RFC 4291 2.5.5.2), so one comparison serves both.
using IpBytes = std::array<std::uint8_t, 16>;

/// Who is at the other end of a session, as its transport knows it. The
/// transport tells the session once, before the first byte.
struct Peer {
  enum class Kind : std::uint8_t {
    kUnknown,  ///< not told (a session used on its own): may control, as before access control
    kIpv4,     ///< a network client; `ipv4` holds its address
    kOther,    ///< a network client whose address the transport could not read
    kLine,     ///< a pty, serial port or USB CDC port: access.serial_control decides
    kIpv6,     ///< a network client; `ipv6` holds its address (never v4-mapped)
  };
  Kind kind = Kind::kUnknown;
  std::uint32_t ipv4 = 0;  ///< host order (192.168.1.20 = 0xC0A80114)
  IpBytes ipv6{};          ///< network order

  static Peer from_ipv4(std::uint32_t address) { return {Kind::kIpv4, address, {}}; }
  /// An IPv4-mapped address (an IPv4 client of a dual-stack socket) is an
  /// IPv4 client: the allow-list's IPv4 entries and the per-address caps
  /// treat it as the host it is.
  static Peer from_ipv6(const IpBytes& address);
  static Peer line() { return {Kind::kLine, 0, {}}; }

  bool is_network() const { return kind == Kind::kIpv4 || kind == Kind::kIpv6; }
  /// The address in 16 bytes (zeros unless is_network()).
  IpBytes address() const;
  /// What per-host limits count by (the per-address caps, the login
  /// limiter, the log's summaries): an IPv4 address, or the /64 of an IPv6
  /// one, since one IPv6 host picks any address of its /64 at will (SLAAC
  /// privacy addresses, RFC 8981) and a /64 is the least a site is given
  /// (docs/security.md, "IPv6").
  IpBytes host_key() const;
  /// 32 bits that tell addresses apart: the IPv4 address, or a hash (FNV-1a)
  /// of the IPv6 one.
  std::uint32_t address_hash() const;
  /// Same kind and, for network clients, the same host_key().
  bool same_host(const Peer& other) const;
};

/// Longest text of an address: an IPv6 address with an embedded IPv4 and a
/// "/64", and the terminating zero.
inline constexpr std::size_t kAddressTextBytes = 48;

/// The usual text of an address: "192.168.1.20", "2001:db8::1" (RFC 5952:
/// lowercase, the longest run of zero groups as "::"), "::ffff:10.0.0.1".
/// Returns `out`.
const char* address_text(const IpBytes& address, char (&out)[kAddressTextBytes]);

/// A client for the log: its address ("192.168.1.20", "2001:db8::7"; an
/// IPv6 one as its /64's first address when `host` is set: Peer::host_key),
/// or "a serial port", "a network client", "an unknown client".
const char* peer_text(const Peer& peer, char (&out)[kAddressTextBytes], bool host = false);

}  // namespace rotord::access
