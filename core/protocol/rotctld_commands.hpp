#pragma once
#include <cstdint>
#include <span>
#include <string_view>

namespace rotord::protocol::rotctld {

/// What a command does (one per row of rotctl 4.5.4's test_list, plus
/// get_conf and dump_conf from Hamlib 4.6).
enum class Op : std::uint8_t {
  kSetPos,
  kGetPos,
  kPark,
  kStop,
  kReset,
  kMove,
  kSetLevel,
  kGetLevel,
  kSetFunc,
  kGetFunc,
  kSetParm,
  kGetParm,
  kSetConf,
  kGetConf,
  kGetInfo,
  kGetStatus,
  kSendCmd,
  kDumpCaps,
  kDumpState,
  kLonLat2Loc,
  kLoc2LonLat,
  kDms2Dec,
  kDec2Dms,
  kDmmm2Dec,
  kDec2Dmmm,
  kQrb,
  kAzSp2AzLp,
  kDistSp2DistLp,
  kPause,
  kDumpConf,
};

struct Command {
  unsigned char code;  ///< short form; 0x8f, 0x8c, 0xad are Hamlib's internal codes
  const char* name;    ///< long form, used after '\' and in extended replies
  Op op;
  std::uint8_t args;  ///< whitespace-separated arguments read after the command
  /// Hamlib's ARG_OUT: the command returns values, so success adds no
  /// `RPRT 0` in the default protocol.
  bool returns_values;
  /// send_cmd takes the rest of the line as its one argument.
  bool line_argument;
  /// Moves the rotator or changes a setting: refused to a read-only client
  /// (access::may_control). Stop is not among them: anyone may stop.
  bool changes_state;
};

/// Every command, in rotctl's order (docs/protocols/rotctld.md is checked
/// against it: tests/docs).
std::span<const Command> commands();
const Command* find_command(unsigned char code);
const Command* find_command(std::string_view long_name);

}  // namespace rotord::protocol::rotctld
