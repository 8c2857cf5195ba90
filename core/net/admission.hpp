#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "access/peer.hpp"
#include "util/time.hpp"

namespace rotord::settings {
class Settings;
}

namespace rotord::net {

/// How long a stop-only exchange (Admission::Decision::Kind::kStopOnly) waits
/// for its one command before the port's busy refusal and the close.
inline constexpr Millis kStopOnlyExchangeMs = 2000;

/// A client's network address, the key of the per-address cap: IPv6 as it
/// is, IPv4 as ::ffff:a.b.c.d (so a v4-mapped client of a v6 socket is the
/// same host as a plain IPv4 one).
struct Address {
  std::array<std::uint8_t, 16> bytes{};

  static Address from_ipv4(std::uint32_t host_order);
  static Address from_ipv6(const std::uint8_t (&network_order)[16]);
  friend bool operator==(const Address&, const Address&) = default;
};

/// What a transport keeps of one open connection for the admission rule.
struct ClientInfo {
  access::Peer peer;          ///< for the allow-list (access.control_networks)
  Address address;            ///< for the per-address cap
  bool event_stream = false;  ///< an HTTP event stream (protocol::Session::is_event_stream)
  /// An HTTP keep-alive connection waiting for its next request: nothing in
  /// progress, so it makes room at once (a browser opens another when it
  /// needs one), without waiting for net.idle_evict_s.
  bool between_requests = false;
  /// Admitted over capacity for one exchange in which only STOP is obeyed
  /// (Decision::Kind::kStopOnly); counted apart from every other limit.
  bool stop_only = false;
  Millis opened_ms = 0;
  Millis last_receive_ms = 0;  ///< the last byte from the client, or opened_ms
  /// The last command the protocol knew (protocol::Session::commands), or
  /// opened_ms: what "idle" and "least recently useful" are measured by. Bare
  /// line ends and unknown words keep a connection warm, not used.
  Millis last_useful_ms = 0;
};

/// The open connections of one server, as the transport holds them.
class ClientList {
 public:
  virtual ~ClientList() = default;
  virtual std::size_t size() const = 0;
  /// nullptr: entry `i` is a free slot (the Pico's fixed slots).
  virtual const ClientInfo* at(std::size_t i) const = 0;
};

/// Connection numbers of one server, in plain integers for /metrics. Each
/// counts since the server started.
struct ConnectionCounters {
  std::uint32_t accepted = 0;
  std::uint32_t refused_full = 0;          ///< full, nobody idle enough to drop: refused as before
  std::uint32_t refused_per_address = 0;   ///< its host already had net.max_per_address
  std::uint32_t evicted_idle = 0;          ///< dropped for a newcomer after net.idle_evict_s
  std::uint32_t evicted_event_stream = 0;  ///< oldest event stream dropped (HTTP only)
  std::uint32_t dropped_backlog = 0;       ///< stopped reading; its output overflowed
  std::uint32_t stop_only = 0;             ///< admitted over capacity for one STOP-only exchange
  std::uint32_t evicted_for_listed = 0;    ///< a busy client dropped for an allow-listed newcomer
};

/// The fixed limits of one server; the rest is read from the settings at
/// each decision, so a changed setting applies to the next newcomer.
struct Limits {
  /// Request and line clients (net.max_clients, clamped to the slots).
  std::size_t max_clients = 8;
  /// Every connection together, event streams included: the Pico's static
  /// slots. Unbounded on Linux (the two limits bound the total there).
  std::size_t slots = SIZE_MAX;
  /// Event streams apart from max_clients; 0: the protocol has none.
  std::size_t max_event_streams = 0;
  /// Stop-only exchanges at once, apart from the rest (one per host). The
  /// Pico has one extra static slot per server for them.
  std::size_t stop_only_slots = 0;
};

/// Who gets a connection slot, shared by every transport (Linux asio, the Pico
/// W's lwIP) so "STOP is never locked out" holds the same everywhere
/// (docs/security.md, "Availability"):
///
/// - only clients doing something count: "idle" is measured from the last
///   command the protocol knew (ClientInfo::last_useful_ms), so a client that
///   only sends line ends is idle. A full port makes room by dropping the
///   client idle longest, when it has been idle for net.idle_evict_s and is
///   not on access.control_networks;
/// - an allow-listed newcomer is served before strangers: it drops the
///   stranger least recently useful, however busy; with no stranger left,
///   the listed client least recently useful gives way;
/// - one host holds at most net.max_per_address of the request/line slots
///   (an IPv6 host is its /64, unless it is on the allow-list: same_host),
///   and never all of them (the cap is kept below max_clients); at its cap a
///   host's newcomer replaces that host's own client idle longest, allowed
///   or not (a host that lost its connections without a close, e.g. a
///   rebooted PC, gets back in);
/// - a newcomer that still finds no room is not refused outright: it gets
///   one short exchange (kStopOnly, kStopOnlyExchangeMs) in which only STOP
///   is obeyed, within Limits::stop_only_slots and one per host; only when
///   those are taken too is it refused, in the protocol's own way;
/// - HTTP event streams do not count against max_clients nor the per-address
///   cap; they have their own limit, and a newer stream, or a newcomer
///   finding every static slot taken, drops the oldest stream first.
///
/// No heap: it reads the transport's list in place.
class Admission {
 public:
  struct Decision {
    enum class Kind : std::uint8_t { kAdmit, kStopOnly, kRefuseFull, kRefusePerAddress };
    Kind kind = Kind::kAdmit;
    /// kAdmit only: the entry to drop first to make room, or kNone.
    std::size_t evict = kNone;
  };
  static constexpr std::size_t kNone = SIZE_MAX;

  /// `settings` null: no per-address cap and no eviction (the old rule).
  Admission(Limits limits, const settings::Settings* settings)
      : limits_(limits), settings_(settings) {}

  /// A client connects; counts the outcome.
  Decision admit(const ClientList& clients, const ClientInfo& newcomer, Millis now);
  /// Entry `self` has just become an event stream: the stream to drop to stay
  /// within the limit (the oldest other one), or kNone; counts it.
  std::size_t stream_started(const ClientList& clients, std::size_t self);

  /// The per-address cap in force: net.max_per_address, below max_clients.
  std::size_t per_address_cap() const;
  /// net.idle_evict_s in ms; -1: never (no settings).
  Millis idle_evict_ms() const;
  /// On a non-empty access.control_networks: never dropped for a stranger.
  bool control_listed(const access::Peer& peer) const;

  const Limits& limits() const { return limits_; }
  ConnectionCounters& counters() { return counters_; }
  const ConnectionCounters& counters() const { return counters_; }

 private:
  /// The request/line client idle longest (idle at least idle_evict_ms), of
  /// `only`'s host when given; allow-listed ones only when `any_listed`.
  std::size_t idlest(const ClientList& clients, const ClientInfo* only, bool any_listed,
                     Millis now) const;
  /// One host for the per-address cap: the same address, or two IPv6
  /// addresses of one /64 when neither is on the allow-list.
  bool same_host(const ClientInfo& a, const ClientInfo& b) const;
  /// The request/line client least recently useful, however recently,
  /// among the allow-listed ones (`listed`) or the others.
  std::size_t least_useful(const ClientList& clients, bool listed) const;
  /// No room: a stop-only exchange if one is free for this host, else `refusal`.
  Decision stop_only_or(const ClientList& clients, const ClientInfo& newcomer,
                        Decision::Kind refusal);
  std::size_t oldest_stream(const ClientList& clients, std::size_t except) const;

  Limits limits_;
  const settings::Settings* settings_;
  ConnectionCounters counters_;
};

}  // namespace rotord::net
