#pragma once
#include <cstddef>
#include <string_view>

#include "protocol/line_reply.hpp"

namespace rotord::protocol::rotctld {

/// Hamlib error codes (enum rig_errcode_e, include/hamlib/rig.h); rotctld
/// sends them negated: `RPRT -1` is RIG_EINVAL.
enum class HamlibError : int {
  kOk = 0,
  kInvalid = 1,         ///< RIG_EINVAL: bad number, out of range, unknown token
  kNotImplemented = 4,  ///< RIG_ENIMPL: a command rotctld does not know
  kIo = 6,              ///< RIG_EIO: no position reading / no raw port
  kRejected = 9,        ///< RIG_ERJCTED: the rotator refuses (fault, limit)
  kTruncated = 10,      ///< RIG_ETRUNC: the reply does not fit (never in practice)
  kNotAvailable = 11,   ///< RIG_ENAVAIL: e.g. elevation on an azimuth-only rotator
};

/// One whole reply, written with a single ByteSink::write (Gpredict reads
/// each reply with one recv); the longest is dump_caps. One that cannot fit
/// is RIG_ETRUNC's `RPRT -10` (line_reply.hpp: the policy of every line
/// protocol).
inline constexpr std::size_t kReplyCapacity = 1536;
inline constexpr ReplyRules kReplyRules{"\n", "RPRT -10\n"};
using ReplyBuffer = LineReply<kReplyCapacity>;

}  // namespace rotord::protocol::rotctld
