#pragma once
// Failed web logins, per client address: after kFreeFailures in a row an
// address waits before its next try, 1 s doubling to 5 min; a success
// clears it. The slow hash already limits everyone together (one login is
// checked at a time), this keeps one host from guessing at that rate.
#include <array>
#include <cstdint>

#include "access/peer.hpp"
#include "util/time.hpp"

namespace rotord::access {

class LoginLimiter {
 public:
  /// Addresses remembered; a new one replaces the one idle longest. An IPv6
  /// client is remembered by its /64 (Peer::host_key).
  static constexpr std::size_t kAddresses = 8;
  static constexpr unsigned kFreeFailures = 3;
  static constexpr Millis kFirstWaitMs = 1000;
  static constexpr Millis kMaxWaitMs = 5 * 60 * 1000;

  /// How long `peer` must still wait before it may try again (0: now).
  Millis wait_ms(const Peer& peer, Millis now) const;
  /// Counts a failure; returns the failures in a row from that address.
  unsigned failed(const Peer& peer, Millis now);
  void succeeded(const Peer& peer);

 private:
  struct Entry {
    bool used = false;
    Peer who;
    unsigned failures = 0;
    Millis last = 0;
    Millis blocked_until = 0;
  };
  Entry* find(const Peer& peer);
  const Entry* find(const Peer& peer) const;

  std::array<Entry, kAddresses> entries_{};
};

}  // namespace rotord::access
