#pragma once
// The one list of UDP rotor protocols both ports serve (docs/protocols/udp.md):
// Linux (ports/linux/udp_server.cpp, asio) and the Pico W
// (ports/pico_w/lwip_udp.cpp, a raw lwIP pcb). Each row names its settings;
// a port opens the rows that are enabled, on their port, at start.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "protocol/n1mm_rotor.hpp"
#include "protocol/pst_rotor.hpp"
#include "settings/settings.hpp"

namespace rotord::protocol {

enum class DatagramPersonality : std::uint8_t { kN1mm, kPst };
inline constexpr std::size_t kDatagramPersonalityCount = 2;

struct DatagramInfo {
  DatagramPersonality personality;
  std::string_view key;   ///< n1mm, pst: the settings' prefix
  std::string_view name;  ///< for logs
  settings::Id enabled;   ///< off by default: UDP senders can be forged
  settings::Id port;
};

/// Every UDP protocol, in the order of DatagramPersonality.
std::span<const DatagramInfo> datagram_protocols();

/// One handler per row, on one controller: what a port owns and feeds.
class DatagramHandlers {
 public:
  explicit DatagramHandlers(Controller& controller) : n1mm_(controller), pst_(controller) {}
  DatagramProtocol& get(DatagramPersonality p) {
    if (p == DatagramPersonality::kN1mm) return n1mm_;
    return pst_;
  }

 private:
  N1mmRotor n1mm_;
  PstRotor pst_;
};

}  // namespace rotord::protocol
