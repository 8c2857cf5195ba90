#pragma once
#include <cstdint>

namespace rotord::access {

/// Who is at the other end of a session, as its transport knows it. The
/// transport tells the session once, before the first byte.
struct Peer {
  enum class Kind : std::uint8_t {
    kUnknown,  ///< not told (a session used on its own): may control, as before access control
    kIpv4,     ///< a network client; `ipv4` holds its address
    kOther,    ///< a network client the IPv4 allow-list cannot name (IPv6)
    kLine,     ///< a pty, serial port or USB CDC port: access.serial_control decides
  };
  Kind kind = Kind::kUnknown;
  std::uint32_t ipv4 = 0;  ///< host order (192.168.1.20 = 0xC0A80114)

  static Peer from_ipv4(std::uint32_t address) { return {Kind::kIpv4, address}; }
  static Peer line() { return {Kind::kLine, 0}; }
};

}  // namespace rotord::access
