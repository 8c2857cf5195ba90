#pragma once
#include <cstdint>
#include <span>
#include <string_view>

#include "protocol/datagram.hpp"

namespace rotord::protocol {

/// PstRotator's UDP control protocol (docs/protocols/udp.md), which rotord
/// serves in PstRotator's place: `<PST><AZIMUTH>85</AZIMUTH></PST>`,
/// `<ELEVATION>`, `<STOP>1</STOP>`, `<PARK>1</PARK>`, `<QRA>KN34BJ</QRA>`,
/// several in one message, and the queries `<PST>AZ?</PST>` and
/// `<PST>EL?</PST>`, answered `AZ:123` / `EL:45` (CR ended) to the sender's
/// address at pst.port + 1. Commands get no reply and bad input none either
/// (the protocol has no error message): a message with anything malformed
/// or unknown in it is ignored whole.
class PstRotor final : public DatagramProtocol {
 public:
  enum class Arg : std::uint8_t {
    kNumber,   ///< a number in degrees (also Hamlib 4.6's "85.000000.2")
    kSwitch,   ///< 1 acts, 0 does nothing
    kLocator,  ///< a Maidenhead locator
    kQuery,    ///< bare text, no value
  };
  enum class Action : std::uint8_t {
    kAzimuth,
    kElevation,
    kStop,
    kPark,
    kQra,
    kTrack,
    kAzQuery,
    kElQuery
  };
  /// One row of the command table (pst_rotor.cpp); docs/protocols/udp.md
  /// lists the same rows (tests/docs).
  struct Command {
    std::string_view name;  ///< the element's name, or the query's text
    Arg arg;
    Action action;
    std::string_view help;
    /// Moves the rotator: not obeyed from a read-only sender. STOP never is.
    bool changes_state;
  };
  static std::span<const Command> commands();

  explicit PstRotor(Controller& controller) : controller_(controller) {}

  DatagramOutcome receive(std::string_view datagram, const access::Peer& from,
                          DatagramReplies& out) override;

 private:
  Controller& controller_;
};

}  // namespace rotord::protocol
