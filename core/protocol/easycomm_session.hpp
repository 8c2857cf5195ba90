#pragma once
#include <optional>

#include "protocol/line_assembler.hpp"
#include "protocol/session.hpp"
#include "util/axis_id.hpp"
#include "util/direction.hpp"

namespace rotord::protocol {

/// Easycomm I/II/III as Hamlib's backends 201, 202 and 204 speak it (see
/// docs/protocols/easycomm.md). Lines end in CR, LF or CRLF; a line holds
/// commands separated by spaces (or the stray ';' Hamlib 4.5.4 appends to
/// configuration commands). Set, move and stop commands are silent (Hamlib
/// never reads a reply to them); queries answer one line ending in LF.
/// Rejected input is answered with an `AL<REASON>` alarm line, the only error
/// report Easycomm defines, and changes nothing.
class EasycommSession final : public Session {
 public:
  static constexpr std::size_t kMaxLineLength = 128;
  static constexpr std::size_t kMaxReplyLength = 160;
  static constexpr std::string_view kTooManyConnections = "ALBUSY\n";

  EasycommSession(Controller& controller, const char* version)
      : controller_(controller), version_(version) {}

  void receive(std::string_view bytes, ByteSink& out) override;

  /// Handles one line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

  /// Easycomm III velocities are in mdeg/s, but Hamlib 204 writes
  /// (speed - 1) * 100 for its speed level 1..100, so that is the mapping that
  /// round-trips: 0 -> 1 %, 4900 -> 50 %, 9900 and above -> 100 %.
  static int speed_pct_from_velocity(long mdeg_s) {
    return mdeg_s >= 9900 ? 100 : mdeg_s <= 0 ? 1 : static_cast<int>(mdeg_s / 100) + 1;
  }

 private:
  /// What a line asks for, collected first so `AZx ELy` is one go-to and
  /// `AZ EL` one combined reply (Hamlib 4.5 needs both on one line).
  struct LineRequest {
    std::optional<float> set_az_deg;
    std::optional<float> set_el_deg;
    bool query_az = false;
    bool query_el = false;
    bool stop_az = false;
    bool stop_el = false;
  };

  /// Checks one token and notes AZ/EL/SA/SE; false (after an alarm) when it
  /// is malformed. `rest` loses the tokens a command takes as arguments.
  bool parse_token(std::string_view token, std::string_view& rest, LineRequest& request,
                   ByteSink& out);
  /// Runs one checked token (AZ/EL/SA/SE wait for finish_line).
  void run_token(std::string_view token, std::string_view& rest, ByteSink& out);
  void move(AxisId axis, Direction dir, std::string_view velocity, ByteSink& out);
  void read_config(std::string_view reg, ByteSink& out);
  void write_config(std::string_view arg, ByteSink& out);
  void finish_line(const LineRequest& request, ByteSink& out);
  int status_register() const;
  int error_register() const;

  Controller& controller_;
  const char* version_;
  LineAssembler<kMaxLineLength> lines_;
};

}  // namespace rotord::protocol
