#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hal/monotonic_clock.hpp"
#include "metrics/tick_source.hpp"
#include "protocol/datagram_registry.hpp"
#include "protocol/metrics_protocol.hpp"
#include "protocol/protocol_registry.hpp"

namespace rotord::metrics {

/// HTTP and each line protocol of the registry.
inline constexpr std::size_t kProtocolCount = 1 + protocol::kPersonalityCount;

/// "http", "wrc", "rotctld", "gs232", "easycomm", "seed", "console".
const char* protocol_label(Protocol protocol);

/// Whether one reply unit a session wrote is that protocol's error (WRC
/// `ERROR ...`, rotctld `RPRT -n`, GS-232 `?>`, Easycomm `AL...`, seed
/// `$ERR,...`, an HTTP status of 400 or more). Sessions write each reply as
/// one unit (protocol::ByteSink), so transports classify what they send
/// instead of every error path counting for itself.
bool is_error_reply(Protocol protocol, std::string_view reply);

/// What the transports of one protocol count. Plain fields: everything runs
/// in the port's one loop (asio thread, the Pico's poll loop).
struct ProtocolCounters {
  std::uint32_t open = 0;           ///< connections open now (TCP)
  std::uint64_t accepted = 0;       ///< connections accepted since start
  std::uint64_t refused = 0;        ///< newcomers refused at the connection limit
  std::uint64_t evicted = 0;        ///< clients dropped to make room for a newcomer
  std::uint64_t errors = 0;         ///< error replies (is_error_reply), every transport
  std::uint64_t auth_failures = 0;  ///< failed logins, refused tokens (access control)

  void on_accept() {
    ++accepted;
    ++open;
  }
  void on_close() {
    if (open > 0) --open;
  }
  void on_refuse() { ++refused; }
  void on_evict() { ++evicted; }
  void on_auth_failure() { ++auth_failures; }
};

/// Everything a port counts outside the controller, for GET /metrics and
/// GET /healthz. The port owns one (no global); transports get a pointer to
/// their protocol's counters, the web API a pointer to the whole.
class Registry {
 public:
  ProtocolCounters& protocol(Protocol p) { return protocols_[static_cast<std::size_t>(p)]; }
  const ProtocolCounters& protocol(Protocol p) const {
    return protocols_[static_cast<std::size_t>(p)];
  }
  /// The transport's hook for every reply unit it sends.
  void on_reply(Protocol p, std::string_view reply) {
    if (is_error_reply(p, reply)) ++protocol(p).errors;
  }
  /// The UDP transports' hook for every datagram they hand their protocol.
  void on_datagram(protocol::DatagramPersonality p, protocol::DatagramOutcome outcome) {
    ++datagrams_[static_cast<std::size_t>(p)][static_cast<std::size_t>(outcome)];
  }
  std::uint64_t datagrams(protocol::DatagramPersonality p,
                          protocol::DatagramOutcome outcome) const {
    return datagrams_[static_cast<std::size_t>(p)][static_cast<std::size_t>(outcome)];
  }

  /// The loop's tick schedule (period, jitter, overruns): the port's
  /// TickScheduler; nullptr: not reported.
  const TickSource* ticks = nullptr;
  /// Settings documents written and writes that failed, as the settings
  /// saver counts them: the port points these at SettingsSaver::writes() and
  /// failures() (the saver is in storage, which this layer does not reach);
  /// nullptr: not reported.
  const std::uint32_t* settings_writes = nullptr;
  const std::uint32_t* settings_failures = nullptr;
  /// The wear odometer's records written and failed (care::OdometerSaver,
  /// docs/care.md); nullptr: not reported.
  const std::uint32_t* odometer_writes = nullptr;
  const std::uint32_t* odometer_failures = nullptr;
  /// The scheduler's clock, for the age of the last tick (GET /healthz).
  const hal::MonotonicClock* clock = nullptr;
  /// The clock's reading when the port started, for rotord_uptime_seconds.
  std::int64_t start_us = 0;
  /// Whether GET /metrics carries the `# HELP` lines (about 3.8 KB of the
  /// page's 11 KB); the Pico W leaves them out to fit its TCP buffers.
  bool help_text = true;

 private:
  std::array<ProtocolCounters, kProtocolCount> protocols_{};
  std::array<std::array<std::uint64_t, protocol::kDatagramOutcomeCount>,
             protocol::kDatagramPersonalityCount>
      datagrams_{};
};

}  // namespace rotord::metrics
