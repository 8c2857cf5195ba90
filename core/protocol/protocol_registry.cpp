#include "protocol/protocol_registry.hpp"

#include <array>

namespace rotord::protocol {
namespace {

using P = Personality;

// One row per personality, in the order of Personality. Seed's TCP port is
// new with the Pico W serving it (issue 11): next to GS-232's and
// Easycomm's; the Linux daemon leaves it off unless --seed-port is given,
// as before.
constexpr std::array<ProtocolInfo, kPersonalityCount> kProtocols = {{
    {P::kWrc, "wrc", "WRC text protocol", 1234, true, 9600, WrcSession::kTooManyConnections,
     metrics::Protocol::kWrc},
    // Hamlib rotctld (Gpredict, SatNOGS, rotctl -m 2): no greeting, one write per reply.
    {P::kRotctld, "rotctld", "Hamlib rotctld", 4533, true, 9600,
     RotctldSession::kTooManyConnections, metrics::Protocol::kRotctld},
    // Yaesu GS-232A/B; which one follows gs232.variant, read per command.
    // The real controllers and Hamlib's backends run at 9600 baud.
    {P::kGs232, "gs232", "Yaesu GS-232", 4601, true, 9600, Gs232Session::kTooManyConnections,
     metrics::Protocol::kGs232},
    // Hamlib's Easycomm backends default to 19200 baud.
    {P::kEasycomm, "easycomm", "Easycomm II/III", 4602, true, 19200,
     EasycommSession::kTooManyConnections, metrics::Protocol::kEasycomm},
    {P::kSeed, "seed", "seed $cmd protocol", 4603, false, 9600, SeedSession::kTooManyConnections,
     metrics::Protocol::kSeed},
    // The console (configuration, calibration, fault reset, reboot) for a
    // person at a terminal: a pty or serial line on Linux, the Pico's USB
    // log port. Never on TCP unless --console-port is given (the web and
    // REST do all of it on the network); the Pico serves it on USB only.
    {P::kConsole, "console", "rotord console", 4604, false, 115200,
     ConsoleSession::kTooManyConnections, metrics::Protocol::kConsole},
}};

}  // namespace

std::span<const ProtocolInfo> protocols() {
  return kProtocols;
}

const ProtocolInfo& protocol_info(Personality personality) {
  return kProtocols[static_cast<std::size_t>(personality)];
}

const ProtocolInfo* find_protocol(std::string_view key) {
  for (const ProtocolInfo& p : kProtocols) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

}  // namespace rotord::protocol
