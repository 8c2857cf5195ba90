#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "access/peer.hpp"

namespace rotord {

class Controller;

namespace protocol {

/// The replies one datagram gets. Each goes back to the sender's address
/// at its own UDP port (PstRotator: its port + 1; N1MM+: 13010), one
/// datagram each. Fixed room: a protocol answers at most kMaxReplies.
class DatagramReplies {
 public:
  static constexpr std::size_t kMaxReplies = 2;
  static constexpr std::size_t kMaxBytes = 80;
  struct Reply {
    std::uint16_t port = 0;
    std::size_t size = 0;
    std::array<char, kMaxBytes> bytes{};
    std::string_view text() const { return {bytes.data(), size}; }
  };

  /// Adds one reply (printf format); false, and nothing added, when it
  /// does not fit or there is no room left.
  bool add(std::uint16_t port, const char* fmt, ...) __attribute__((format(printf, 3, 4)));
  std::size_t count() const { return count_; }
  const Reply& operator[](std::size_t i) const { return items_[i]; }

 private:
  std::array<Reply, kMaxReplies> items_{};
  std::size_t count_ = 0;
};

/// What became of a datagram: what the port logs (debug) and tests check.
enum class DatagramOutcome : std::uint8_t {
  kDone,       ///< obeyed (or answered)
  kNotForUs,   ///< well formed, for another rotor (N1MM+ rotor name)
  kMalformed,  ///< not the protocol's format: nothing done
  kOversize,   ///< longer than kMaxDatagramBytes: nothing read
  kRefused,    ///< a read-only sender asked for a move: refused (STOP and queries still served)
  kFailed,     ///< the controller refused it (out of range, a fault)
};
inline constexpr std::size_t kDatagramOutcomeCount = 6;
/// For the log: "malformed, ignored".
const char* outcome_name(DatagramOutcome outcome);
/// For GET /metrics: "malformed".
const char* outcome_label(DatagramOutcome outcome);

/// A protocol of whole UDP datagrams (docs/protocols/udp.md): each
/// datagram is one message, read whole or not at all, with no connection
/// and no session. The same object is unit-tested, fuzzed and served by
/// both ports (asio on Linux, a lwIP raw UDP pcb on the Pico W).
class DatagramProtocol {
 public:
  /// Longer datagrams are never parsed (the ports read one byte more to
  /// know). N1MM+'s and PstRotator's messages are under 200 bytes.
  static constexpr std::size_t kMaxDatagramBytes = 512;

  virtual ~DatagramProtocol() = default;
  /// One datagram from `from`; the replies it gets go into `out`.
  virtual DatagramOutcome receive(std::string_view datagram, const access::Peer& from,
                                  DatagramReplies& out) = 0;
  /// Called by the port after every control tick: a datagram the protocol
  /// sends by itself (N1MM+'s heading while the rotator turns) goes into
  /// `out`, to the IPv4 address in `to`; false when there is none.
  virtual bool poll(DatagramReplies& /*out*/, access::Peer& /*to*/) { return false; }
};

}  // namespace protocol
}  // namespace rotord
