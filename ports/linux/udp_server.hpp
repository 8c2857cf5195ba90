#pragma once
#include <array>
#include <asio.hpp>
#include <cstdint>
#include <string>

#include "metrics/registry.hpp"
#include "protocol/datagram_registry.hpp"

namespace rotord::linux_port {

/// Serves one UDP rotor protocol (docs/protocols/udp.md) on one port, in
/// the asio thread that also runs the control tick, so the handler calls
/// the controller without locks. Each datagram is read whole into a fixed
/// buffer one byte longer than the protocol reads, so an oversize one is
/// known and ignored; replies go back from this socket to the sender's
/// address at the port the protocol names. Broadcasts to the port arrive
/// too (N1MM+ may broadcast its rotor messages).
class UdpServer {
 public:
  /// Datagrams are counted in `metrics` (GET /metrics) under `personality`;
  /// nullptr counts nothing.
  UdpServer(asio::io_context& io, const asio::ip::address& bind, std::uint16_t port,
            std::string name, protocol::DatagramProtocol& protocol,
            protocol::DatagramPersonality personality, metrics::Registry* metrics = nullptr);
  UdpServer(const UdpServer&) = delete;
  UdpServer& operator=(const UdpServer&) = delete;

  std::uint16_t port() const { return port_; }
  const std::string& name() const { return name_; }
  /// After every control tick: what the protocol sends by itself (N1MM+'s
  /// heading while the rotator turns).
  void poll();

 private:
  void receive();
  void handle(std::size_t size);
  void send(const protocol::DatagramReplies& replies, const asio::ip::address& to);

  asio::ip::udp::socket socket_;
  std::string name_;
  protocol::DatagramProtocol& protocol_;
  protocol::DatagramPersonality personality_;
  metrics::Registry* metrics_;
  std::uint16_t port_ = 0;
  asio::ip::udp::endpoint from_;
  std::array<char, protocol::DatagramProtocol::kMaxDatagramBytes + 1> buffer_{};
};

}  // namespace rotord::linux_port
