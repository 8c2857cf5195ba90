#pragma once
#include <cstdint>
#include <span>
#include <string_view>

#include "protocol/datagram.hpp"
#include "util/time.hpp"

namespace rotord::protocol {

/// The rotor messages N1MM Logger+ sends to a rotor program over UDP
/// (docs/protocols/udp.md), e.g.
///   <N1MMRotor><rotor>Yagi 20</rotor><goazi>330.0</goazi><offset>0</offset>
///   <bidirectional>0</bidirectional><freqband>14</freqband></N1MMRotor>
///   <N1MMRotor><stop>Yagi 20</stop></N1MMRotor>
/// A message for another rotor (n1mm.rotor_name) is left alone. N1MM+ has
/// no error reply: bad input is ignored, and after each message for this
/// rotor the heading goes back as `<name> @ <tenths>` (n1mm.report_port),
/// then every second while the rotator turns and once when it stops, to the
/// last sender, so N1MM+'s rotor window follows the antenna.
class N1mmRotor final : public DatagramProtocol {
 public:
  /// What an element's value must be.
  enum class Value : std::uint8_t {
    kName,     ///< text, the rotor's name (entities allowed)
    kBearing,  ///< a number 0..360
    kOffset,   ///< a number -360..360
    kFlag,     ///< 0 or 1 (also True / False)
    kNumber,   ///< any number (the band in MHz; ignored)
  };
  /// One row of the element table (n1mm_rotor.cpp); docs/protocols/udp.md
  /// lists the same rows (tests/docs).
  struct Element {
    std::string_view name;
    Value value;
    std::string_view help;
    /// Asks for a move: not obeyed from a read-only sender
    /// (access.control_networks, the control lock). `stop` never is.
    bool changes_state;
  };
  static std::span<const Element> elements();

  explicit N1mmRotor(Controller& controller) : controller_(controller) {}

  DatagramOutcome receive(std::string_view datagram, const access::Peer& from,
                          DatagramReplies& out) override;
  bool poll(DatagramReplies& out, access::Peer& to) override;

  /// Controller time between two heading reports while the rotator turns.
  static constexpr Millis kReportPeriodMs = 1000;

 private:
  /// The heading report, under `name` when n1mm.rotor_name is empty.
  void report(std::string_view name, DatagramReplies& out) const;

  Controller& controller_;
  // Where the reports go while the rotator turns after a message.
  access::Peer report_to_{};
  bool reporting_ = false;
  Millis next_report_ms_ = 0;
  char report_name_[33] = {};
  std::size_t report_name_size_ = 0;
};

}  // namespace rotord::protocol
