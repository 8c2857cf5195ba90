#pragma once
// A minimal DHCP server for the rotord-setup access point, on lwIP's raw UDP
// API. Hand-written because neither lwIP nor the pico-sdk has one (the SDK's
// cyw43 glue only calls one when built inside MicroPython) and phones drop a
// Wi-Fi network that hands out no address. Portable lwIP code like
// lwip_transport.cpp, so tests/lwip runs it against Debian's lwIP.
//
// Scope: DISCOVER -> OFFER, REQUEST -> ACK or NAK, for a handful of clients
// on one /24; leases are remembered by MAC address until the table is full,
// then reused oldest first. No lease expiry, no relay, no options beyond
// mask, router, server id and lease time.
#include <array>
#include <cstddef>
#include <cstdint>

struct netif;
struct udp_pcb;

namespace rotord::lwip_port {

class DhcpServer {
 public:
  static constexpr std::size_t kMaxLeases = 8;
  /// Offered addresses: the server's /24 with the host part from here up.
  static constexpr std::uint8_t kFirstHost = 16;
  static constexpr std::uint32_t kLeaseSeconds = 24 * 3600;

  DhcpServer() = default;
  ~DhcpServer();
  DhcpServer(const DhcpServer&) = delete;
  DhcpServer& operator=(const DhcpServer&) = delete;

  /// Serves on `itf` (its address is the server's and the clients' router).
  /// False when lwIP has no UDP pcb left or port 67 is taken.
  bool start(netif* itf);
  void stop();
  bool running() const { return pcb_ != nullptr; }

 private:
  struct Lease {
    std::array<std::uint8_t, 6> mac{};
    bool used = false;
  };
  struct Glue;  // the lwIP callback (dhcp_server.cpp)
  void handle(std::size_t length);
  /// Index of the lease of `mac`, allocating one when it has none.
  std::size_t lease_for(const std::uint8_t* mac);
  void reply(std::uint8_t type, std::uint32_t your_ip_be);

  netif* netif_ = nullptr;
  udp_pcb* pcb_ = nullptr;
  std::array<Lease, kMaxLeases> leases_{};
  std::size_t next_reuse_ = 0;
  /// The request being answered and the reply (BOOTP's 548-byte minimum
  /// DHCP message); members, not locals, to keep the callback's stack small.
  std::array<std::uint8_t, 548> in_{};
  std::array<std::uint8_t, 548> out_{};
};

}  // namespace rotord::lwip_port
