#pragma once
// The one list of line protocols (personalities) both ports serve: Linux
// (ports/linux/services.cpp: TCP, --pty, --serial) and the Pico W
// (ports/pico_w/main.cpp: lwIP TCP; usb_personality.cpp: USB CDC). A port
// serves every row on every transport it has unless it says why not; the web
// (HTTP) is apart, on its own port.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "net/dns_sd.hpp"
#include "protocol/console_session.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/metrics_protocol.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"

namespace rotord::protocol {

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
  /// Counted under this protocol in GET /metrics, whose `protocol` label
  /// is the key.
  metrics::Protocol metric;
  /// Whether one reply unit a session wrote is this protocol's error, for
  /// the /metrics error count (metrics::is_error_reply).
  bool (*is_error_reply)(std::string_view reply);
  DnsSd dns_sd;
};

/// Every personality, in the order of Personality.
std::span<const ProtocolInfo> protocols();
const ProtocolInfo& protocol_info(Personality personality);
/// The row of `key` (exact, lower case), or nullptr.
const ProtocolInfo* find_protocol(std::string_view key);
/// The row counted under `metric`, or nullptr (HTTP, which is no row).
const ProtocolInfo* find_protocol(metrics::Protocol metric);

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

/// The session type of each personality, and how to build one: the
/// registry's session factory. A port that sizes storage per protocol (the
/// Pico's static pools) names the type; one that builds at run time uses
/// with_session_type().
template <Personality P>
struct SessionOf;
template <>
struct SessionOf<Personality::kWrc> {
  using type = WrcSession;
  static type make(const SessionDeps& d) { return type(d.controller, d.version, d.monitor_tap); }
};
template <>
struct SessionOf<Personality::kRotctld> {
  using type = RotctldSession;
  static type make(const SessionDeps& d) { return type(d.controller, d.version); }
};
template <>
struct SessionOf<Personality::kGs232> {
  using type = Gs232Session;
  static type make(const SessionDeps& d) { return type(d.controller); }
};
template <>
struct SessionOf<Personality::kEasycomm> {
  using type = EasycommSession;
  static type make(const SessionDeps& d) { return type(d.controller, d.version); }
};
template <>
struct SessionOf<Personality::kSeed> {
  using type = SeedSession;
  static type make(const SessionDeps& d) { return type(d.controller); }
};
template <>
struct SessionOf<Personality::kConsole> {
  using type = ConsoleSession;
  static type make(const SessionDeps& d) { return type(d.controller, d.version, d.console); }
};

/// Room for any one line session, for a port with one transport that serves
/// whichever personality a setting names (the Pico W's USB): built there with
/// placement new from SessionOf<P>::make (guaranteed copy elision: no
/// temporary, which for rotctld would be 2.6 KB of the Pico's stack).
inline constexpr std::size_t kAnySessionBytes = std::max(
    {sizeof(SessionOf<Personality::kWrc>::type), sizeof(SessionOf<Personality::kRotctld>::type),
     sizeof(SessionOf<Personality::kGs232>::type), sizeof(SessionOf<Personality::kEasycomm>::type),
     sizeof(SessionOf<Personality::kSeed>::type), sizeof(SessionOf<Personality::kConsole>::type)});
inline constexpr std::size_t kAnySessionAlign = std::max(
    {alignof(SessionOf<Personality::kWrc>::type), alignof(SessionOf<Personality::kRotctld>::type),
     alignof(SessionOf<Personality::kGs232>::type),
     alignof(SessionOf<Personality::kEasycomm>::type), alignof(SessionOf<Personality::kSeed>::type),
     alignof(SessionOf<Personality::kConsole>::type)});

/// Calls `visit(SessionOf<p>{})` with the personality known at compile time,
/// e.g. to build its session in storage of the caller's choice.
template <typename Visitor>
decltype(auto) with_session_type(Personality p, Visitor&& visit) {
  switch (p) {
    case Personality::kWrc:
      return visit(SessionOf<Personality::kWrc>{});
    case Personality::kRotctld:
      return visit(SessionOf<Personality::kRotctld>{});
    case Personality::kGs232:
      return visit(SessionOf<Personality::kGs232>{});
    case Personality::kEasycomm:
      return visit(SessionOf<Personality::kEasycomm>{});
    case Personality::kSeed:
      return visit(SessionOf<Personality::kSeed>{});
    case Personality::kConsole:
      break;
  }
  return visit(SessionOf<Personality::kConsole>{});
}

}  // namespace rotord::protocol
