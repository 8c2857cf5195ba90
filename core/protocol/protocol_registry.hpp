#pragma once
// The one list of line protocols (personalities) both ports serve: Linux
// (ports/linux/services.cpp: TCP, --pty, --serial) and the Pico W
// (ports/pico_w/main.cpp: lwIP TCP; usb_personality.cpp: USB CDC). A port
// serves every row on every transport it has unless it says why not; the web
// (HTTP) is apart, on its own port.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "net/dns_sd.hpp"
#include "protocol/console_session.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/metrics_protocol.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"

namespace rotord::protocol {

/// The line protocols, one value a row below (kProtocols), in its order.
enum class Personality : std::uint8_t { kWrc, kRotctld, kGs232, kEasycomm, kSeed, kConsole };
inline constexpr std::size_t kPersonalityCount = 6;

/// How DNS-SD (net/dns_sd.hpp) announces a protocol's TCP port.
enum class DnsSd : std::uint8_t {
  kNone,     ///< not at all
  kService,  ///< as the _rotctld._tcp service itself
  kTxt,      ///< as "key=port" in that service's TXT record
};

struct ProtocolInfo {
  Personality personality;
  /// The short name: `--pty KEY`, `--serial KEY:...`, `--KEY-port` (Linux),
  /// the usb.personality choice (Pico W).
  std::string_view key;
  std::string_view name;  ///< for logs and the USB interface name
  /// The TCP port. Linux: the default of `--KEY-port`, or the suggested
  /// number when `tcp_by_default` is false (then 0, off, unless given).
  std::uint16_t tcp_port;
  bool tcp_by_default;
  int serial_baud;  ///< default baud rate of a serial device (Linux --serial)
  /// Sent to a client refused a connection slot, before the close.
  std::string_view refusal;
  /// Counted under this in GET /metrics, whose `protocol` label is the key.
  constexpr metrics::Protocol metric() const { return metrics::line_metric(personality); }
  /// Whether one reply unit a session wrote is this protocol's error, for
  /// the /metrics error count (metrics::is_error_reply).
  bool (*is_error_reply)(std::string_view reply);
  DnsSd dns_sd;
  /// Connection slots on the Pico W's TCP port (its static pools: about
  /// 1 KB of output buffer each, plus the session); 0: not served on the
  /// Pico's network (the console: USB only there).
  std::uint8_t pico_tcp_slots;
};

namespace rows {

// Each protocol's error reply, as its session writes it (metrics counts them).
inline bool wrc_error(std::string_view r) {
  return r.starts_with("ERROR");  // MONITOR's STATE lines and every OK start otherwise
}
inline bool rotctld_error(std::string_view r) {
  return r.find("RPRT -") != std::string_view::npos;  // plain and extended replies alike
}
inline bool gs232_error(std::string_view r) {
  return r == Gs232Session::kError;
}
inline bool easycomm_error(std::string_view r) {
  return r.starts_with("AL");  // the alarm line, Easycomm's only error
}
inline bool seed_error(std::string_view r) {
  return r.starts_with("$ERR");
}
inline bool console_error(std::string_view r) {
  return r.starts_with("error:");
}

using P = Personality;

// One row per personality, in the order of Personality (in the header, so
// that a port sizes static storage from a row at compile time: the Pico
// W's TCP pools). Seed's TCP port is
// new with the Pico W serving it (issue 11): next to GS-232's and
// Easycomm's; the Linux daemon leaves it off unless --seed-port is given,
// as before.
inline constexpr std::array<ProtocolInfo, kPersonalityCount> kProtocols = {{
    {P::kWrc, "wrc", "WRC text protocol", 1234, true, 9600, WrcSession::kTooManyConnections,
     wrc_error, DnsSd::kTxt, 4},
    // Hamlib rotctld (Gpredict, SatNOGS, rotctl -m 2): no greeting, one write per reply.
    {P::kRotctld, "rotctld", "Hamlib rotctld", 4533, true, 9600,
     RotctldSession::kTooManyConnections, rotctld_error, DnsSd::kService, 3},
    // Yaesu GS-232A/B; which one follows gs232.variant, read per command.
    // The real controllers and Hamlib's backends run at 9600 baud.
    {P::kGs232, "gs232", "Yaesu GS-232", 4601, true, 9600, Gs232Session::kTooManyConnections,
     gs232_error, DnsSd::kTxt, 2},
    // Hamlib's Easycomm backends default to 19200 baud.
    {P::kEasycomm, "easycomm", "Easycomm II/III", 4602, true, 19200,
     EasycommSession::kTooManyConnections, easycomm_error, DnsSd::kTxt, 2},
    {P::kSeed, "seed", "seed $cmd protocol", 4603, false, 9600, SeedSession::kTooManyConnections,
     seed_error, DnsSd::kTxt, 2},
    // The console (configuration, calibration, fault reset, reboot) for a
    // person at a terminal: a pty or serial line on Linux, the Pico's USB
    // log port. Never on TCP unless --console-port is given (the web and
    // REST do all of it on the network); the Pico serves it on USB only.
    {P::kConsole, "console", "console", 4604, false, 115200, ConsoleSession::kTooManyConnections,
     console_error, DnsSd::kNone, 0},
}};

}  // namespace rows

/// Every personality, in the order of Personality.
std::span<const ProtocolInfo> protocols();
const ProtocolInfo& protocol_info(Personality personality);
/// The row of `key` (exact, lower case), or nullptr.
const ProtocolInfo* find_protocol(std::string_view key);
/// The row counted under `metric`, or nullptr (HTTP, which is no row).
const ProtocolInfo* find_protocol(metrics::Protocol metric);

/// Whether `choices` ('|'-separated, as an enum setting's) is "off" and
/// then rows' keys, each at most once, in any order: usb.personality's
/// choices (checked at compile time in protocol_registry.cpp). A row need
/// not be offered; a choice that is no row's key (a typo, a key renamed)
/// would leave the USB port silent, so it is refused.
constexpr bool offers_off_and_rows(std::string_view choices) {
  std::array<bool, kPersonalityCount> offered{};
  std::size_t start = 0;
  for (std::size_t n = 0; start <= choices.size(); ++n) {
    std::size_t end = choices.find('|', start);
    if (end == std::string_view::npos) end = choices.size();
    const std::string_view choice = choices.substr(start, end - start);
    start = end + 1;
    if (n == 0) {
      if (choice != "off") return false;
      continue;
    }
    const auto row = std::find_if(rows::kProtocols.begin(), rows::kProtocols.end(),
                                  [choice](const ProtocolInfo& p) { return p.key == choice; });
    if (row == rows::kProtocols.end()) return false;  // no row's key
    bool& seen = offered[static_cast<std::size_t>(row->personality)];
    if (seen) return false;  // twice
    seen = true;
  }
  return true;
}

/// What a port announces by DNS-SD: the web's port, and each row's TCP port
/// as `port_of(personality)` gives it (0: off) where its dns_sd column says.
template <typename PortOf>
net::ServicePorts announced_ports(std::uint16_t web_port, PortOf port_of) {
  net::ServicePorts ports;
  ports.web = web_port;
  for (const ProtocolInfo& p : protocols()) {
    if (p.dns_sd == DnsSd::kService) ports.rotctld = port_of(p.personality);
    if (p.dns_sd == DnsSd::kTxt) ports.add_other(p.key.data(), port_of(p.personality));
  }
  return ports;
}

/// What a port gives every session it builds.
struct SessionDeps {
  Controller& controller;
  const char* version;
  /// Where WRC's MONITOR lines are copied as well (the Pico W's USB log
  /// port); nullptr: nowhere.
  MonitorTap* monitor_tap = nullptr;
  /// What the console needs from the port (reboot, import's working copy);
  /// nullptr: those console commands answer that they are not available.
  const ConsolePort* console = nullptr;
};

// The registry's session factory: how each personality's session is built
// from what the port gives (one overload a protocol), and the session types
// in the order of Personality. A port that sizes storage per protocol (the
// Pico's static pools) names the type with SessionOf<P>; one that builds at
// run time uses with_session_type(). Each returns its session by value:
// guaranteed copy elision builds it where the caller puts it (no temporary,
// which for rotctld would be 2.6 KB of the Pico's stack).
inline WrcSession make_session(std::type_identity<WrcSession>, const SessionDeps& d) {
  return WrcSession(d.controller, d.version, d.monitor_tap);
}
inline RotctldSession make_session(std::type_identity<RotctldSession>, const SessionDeps& d) {
  return RotctldSession(d.controller, d.version);
}
inline Gs232Session make_session(std::type_identity<Gs232Session>, const SessionDeps& d) {
  return Gs232Session(d.controller);
}
inline EasycommSession make_session(std::type_identity<EasycommSession>, const SessionDeps& d) {
  return EasycommSession(d.controller, d.version);
}
inline SeedSession make_session(std::type_identity<SeedSession>, const SessionDeps& d) {
  return SeedSession(d.controller);
}
inline ConsoleSession make_session(std::type_identity<ConsoleSession>, const SessionDeps& d) {
  return ConsoleSession(d.controller, d.version, d.console);
}
/// Never built (only its element types are named).
using SessionTypes = std::tuple<WrcSession, RotctldSession, Gs232Session, EasycommSession,
                                SeedSession, ConsoleSession>;
static_assert(std::tuple_size_v<SessionTypes> == kPersonalityCount, "a session type a row");

template <Personality P>
struct SessionOf {
  using type = std::tuple_element_t<static_cast<std::size_t>(P), SessionTypes>;
  static type make(const SessionDeps& d) { return make_session(std::type_identity<type>{}, d); }
};

namespace detail {
template <typename Types>
struct AnySession;
template <typename... S>
struct AnySession<std::tuple<S...>> {
  static constexpr std::size_t kBytes = std::max({sizeof(S)...});
  static constexpr std::size_t kAlign = std::max({alignof(S)...});
};
}  // namespace detail

/// Room for any one line session, for a port with one transport that serves
/// whichever personality a setting names (the Pico W's USB): built there with
/// placement new from SessionOf<P>::make.
inline constexpr std::size_t kAnySessionBytes = detail::AnySession<SessionTypes>::kBytes;
inline constexpr std::size_t kAnySessionAlign = detail::AnySession<SessionTypes>::kAlign;

/// Calls `visit(SessionOf<p>{})` with the personality known at compile time,
/// e.g. to build its session in storage of the caller's choice.
template <std::size_t I = 0, typename Visitor>
decltype(auto) with_session_type(Personality p, Visitor&& visit) {
  if constexpr (I + 1 < kPersonalityCount) {
    if (static_cast<std::size_t>(p) != I)
      return with_session_type<I + 1>(p, std::forward<Visitor>(visit));
  }
  return visit(SessionOf<static_cast<Personality>(I)>{});
}

}  // namespace rotord::protocol
