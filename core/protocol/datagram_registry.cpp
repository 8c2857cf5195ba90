#include "protocol/datagram_registry.hpp"

#include <array>

namespace rotord::protocol {
namespace {

using P = DatagramPersonality;
using settings::Id;

constexpr std::array<DatagramInfo, kDatagramPersonalityCount> kDatagramProtocols = {{
    // N1MM Logger+ sends to its rotor program's port, 12040.
    {P::kN1mm, "n1mm", "N1MM+ rotor (UDP)", Id::kN1mmEnabled, Id::kN1mmPort},
    // PstRotator's "UDP Control" port, 12000; answers to port + 1.
    {P::kPst, "pst", "PstRotator UDP", Id::kPstEnabled, Id::kPstPort},
}};

}  // namespace

std::span<const DatagramInfo> datagram_protocols() {
  return kDatagramProtocols;
}

}  // namespace rotord::protocol
