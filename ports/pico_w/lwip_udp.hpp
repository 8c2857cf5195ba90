#pragma once
// The Pico W's UDP transport for the core's datagram protocols (N1MM+'s and
// PstRotator's rotor messages, docs/protocols/udp.md), on lwIP's raw UDP
// API. Portable lwIP code like lwip_transport.cpp: the firmware builds it
// against the SDK's lwIP and tests/lwip against Debian's liblwip-dev.
//
// One context, as for TCP: lwIP calls on_recv from the Pico's poll loop, the
// loop that runs the control tick, so the protocol calls the controller
// without locks. Each datagram is copied into a fixed buffer one byte longer
// than the protocol reads (an oversize one is known by its length and
// ignored) and freed at once; replies are sent before the callback returns.
#include <array>
#include <cstddef>
#include <cstdint>

#include "metrics/registry.hpp"
#include "protocol/datagram_registry.hpp"

struct udp_pcb;

namespace rotord::lwip_port {

class UdpService {
 public:
  /// Datagrams are counted in `metrics` (GET /metrics) under `personality`;
  /// nullptr counts nothing.
  UdpService(const char* name, protocol::DatagramProtocol& protocol,
             protocol::DatagramPersonality personality, metrics::Registry* metrics = nullptr)
      : name_(name), protocol_(protocol), personality_(personality), metrics_(metrics) {}
  ~UdpService();
  UdpService(const UdpService&) = delete;
  UdpService& operator=(const UdpService&) = delete;

  /// Listens on every address at `port` (0: an ephemeral port, for tests).
  /// False when lwIP has no UDP pcb left or the port is taken.
  bool start(std::uint16_t port);
  void stop();
  bool running() const { return pcb_ != nullptr; }
  std::uint16_t port() const { return port_; }
  const char* name() const { return name_; }
  /// After every control tick: what the protocol sends by itself (N1MM+'s
  /// heading while the rotator turns).
  void poll();
  /// Datagrams handled, and what became of the last (tests, logs).
  std::uint32_t datagrams() const { return datagrams_; }
  protocol::DatagramOutcome last_outcome() const { return last_outcome_; }

 private:
  struct Glue;
  void handle(std::size_t size, const void* from_addr);
  void send(const protocol::DatagramReplies& replies, const void* to_addr);

  const char* name_;
  protocol::DatagramProtocol& protocol_;
  protocol::DatagramPersonality personality_;
  metrics::Registry* metrics_;
  udp_pcb* pcb_ = nullptr;
  std::uint16_t port_ = 0;
  std::uint32_t datagrams_ = 0;
  protocol::DatagramOutcome last_outcome_ = protocol::DatagramOutcome::kDone;
  std::array<char, protocol::DatagramProtocol::kMaxDatagramBytes + 1> in_{};
};

}  // namespace rotord::lwip_port
