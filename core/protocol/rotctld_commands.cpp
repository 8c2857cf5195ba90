#include "protocol/rotctld_commands.hpp"

#include <array>

namespace rotord::protocol::rotctld {
namespace {

// The order and codes of rotctl_parse.c's test_list (Hamlib 4.5.4); get_conf
// (0xad) and dump_conf ('3') are Hamlib 4.6's.
constexpr std::array<Command, 30> kCommands = {{
    {'P', "set_pos", Op::kSetPos, 2, false, false, true},
    {'p', "get_pos", Op::kGetPos, 0, true, false, false},
    {'K', "park", Op::kPark, 0, false, false, true},
    {'S', "stop", Op::kStop, 0, false, false, false},
    {'R', "reset", Op::kReset, 1, false, false, true},
    {'M', "move", Op::kMove, 2, false, false, true},
    {'V', "set_level", Op::kSetLevel, 2, false, false, true},
    {'v', "get_level", Op::kGetLevel, 1, true, false, false},
    {'U', "set_func", Op::kSetFunc, 2, false, false, false},
    {'u', "get_func", Op::kGetFunc, 1, true, false, false},
    {'X', "set_parm", Op::kSetParm, 2, false, false, false},
    {'x', "get_parm", Op::kGetParm, 1, true, false, false},
    {'C', "set_conf", Op::kSetConf, 2, false, false, true},
    {'_', "get_info", Op::kGetInfo, 0, true, false, false},
    {'s', "get_status", Op::kGetStatus, 0, true, false, false},
    {'w', "send_cmd", Op::kSendCmd, 1, true, true, false},
    {'1', "dump_caps", Op::kDumpCaps, 0, false, false, false},
    {0x8f, "dump_state", Op::kDumpState, 0, true, false, false},
    {'L', "lonlat2loc", Op::kLonLat2Loc, 3, true, false, false},
    {'l', "loc2lonlat", Op::kLoc2LonLat, 1, true, false, false},
    {'D', "dms2dec", Op::kDms2Dec, 4, true, false, false},
    {'d', "dec2dms", Op::kDec2Dms, 1, true, false, false},
    {'E', "dmmm2dec", Op::kDmmm2Dec, 3, true, false, false},
    {'e', "dec2dmmm", Op::kDec2Dmmm, 1, true, false, false},
    {'B', "qrb", Op::kQrb, 4, true, false, false},
    {'A', "a_sp2a_lp", Op::kAzSp2AzLp, 1, true, false, false},
    {'a', "d_sp2d_lp", Op::kDistSp2DistLp, 1, true, false, false},
    {0x8c, "pause", Op::kPause, 1, false, false, false},
    {0xad, "get_conf", Op::kGetConf, 1, true, false, false},
    {'3', "dump_conf", Op::kDumpConf, 0, false, false, false},
}};

}  // namespace

std::span<const Command> commands() {
  return kCommands;
}

const Command* find_command(unsigned char code) {
  for (const Command& c : kCommands) {
    if (c.code == code) return &c;
  }
  return nullptr;
}

const Command* find_command(std::string_view long_name) {
  for (const Command& c : kCommands) {
    if (long_name == c.name) return &c;
  }
  return nullptr;
}

}  // namespace rotord::protocol::rotctld
