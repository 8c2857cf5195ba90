#include "protocol/protocol_registry.hpp"

#include <array>

namespace rotord::protocol {
namespace {

using P = Personality;

// Each protocol's error reply, as its session writes it (metrics counts them).
bool wrc_error(std::string_view r) {
  return r.starts_with("ERROR");  // MONITOR's STATE lines and every OK start otherwise
}
bool rotctld_error(std::string_view r) {
  return r.find("RPRT -") != std::string_view::npos;  // plain and extended replies alike
}
bool gs232_error(std::string_view r) {
  return r == Gs232Session::kError;
}
bool easycomm_error(std::string_view r) {
  return r.starts_with("AL");  // the alarm line, Easycomm's only error
}
bool seed_error(std::string_view r) {
  return r.starts_with("$ERR");
}
bool console_error(std::string_view r) {
  return r.starts_with("error:");
}

// One row per personality, in the order of Personality. Seed's TCP port is
// new with the Pico W serving it (issue 11): next to GS-232's and
// Easycomm's; the Linux daemon leaves it off unless --seed-port is given,
// as before.
constexpr std::array<ProtocolInfo, kPersonalityCount> kProtocols = {{
    {P::kWrc, "wrc", "WRC text protocol", 1234, true, 9600, WrcSession::kTooManyConnections,
     metrics::Protocol::kWrc, wrc_error, DnsSd::kTxt},
    // Hamlib rotctld (Gpredict, SatNOGS, rotctl -m 2): no greeting, one write per reply.
    {P::kRotctld, "rotctld", "Hamlib rotctld", 4533, true, 9600,
     RotctldSession::kTooManyConnections, metrics::Protocol::kRotctld, rotctld_error,
     DnsSd::kService},
    // Yaesu GS-232A/B; which one follows gs232.variant, read per command.
    // The real controllers and Hamlib's backends run at 9600 baud.
    {P::kGs232, "gs232", "Yaesu GS-232", 4601, true, 9600, Gs232Session::kTooManyConnections,
     metrics::Protocol::kGs232, gs232_error, DnsSd::kTxt},
    // Hamlib's Easycomm backends default to 19200 baud.
    {P::kEasycomm, "easycomm", "Easycomm II/III", 4602, true, 19200,
     EasycommSession::kTooManyConnections, metrics::Protocol::kEasycomm, easycomm_error,
     DnsSd::kTxt},
    {P::kSeed, "seed", "seed $cmd protocol", 4603, false, 9600, SeedSession::kTooManyConnections,
     metrics::Protocol::kSeed, seed_error, DnsSd::kTxt},
    // The console (configuration, calibration, fault reset, reboot) for a
    // person at a terminal: a pty or serial line on Linux, the Pico's USB
    // log port. Never on TCP unless --console-port is given (the web and
    // REST do all of it on the network); the Pico serves it on USB only.
    {P::kConsole, "console", "console", 4604, false, 115200, ConsoleSession::kTooManyConnections,
     metrics::Protocol::kConsole, console_error, DnsSd::kNone},
}};

constexpr std::size_t txt_rows() {
  std::size_t n = 0;
  for (const ProtocolInfo& p : kProtocols) n += p.dns_sd == DnsSd::kTxt ? 1 : 0;
  return n;
}
// A row announced in the TXT record needs its room there (net/dns_sd.hpp).
static_assert(txt_rows() <= net::ServicePorts::kMaxOthers, "raise ServicePorts::kMaxOthers");

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

const ProtocolInfo* find_protocol(metrics::Protocol metric) {
  for (const ProtocolInfo& p : kProtocols) {
    if (p.metric == metric) return &p;
  }
  return nullptr;
}

}  // namespace rotord::protocol
