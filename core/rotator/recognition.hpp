#pragma once
#include <cstdint>

#include "rotator/goto_stream.hpp"
#include "tracking/sky_target.hpp"

namespace rotord {

/// Why a recognised pass stopped being followed (docs/tracking.md,
/// "Trackers through the protocols").
enum class RecognitionEnd : std::uint8_t {
  kNone,         ///< not ended (or none yet)
  kDeparted,     ///< the client sent a go-to away from the object: obeyed literally
  kStop,         ///< STOP, from anyone
  kPark,         ///< PARK, from anyone
  kOtherSource,  ///< a go-to from another client: obeyed literally
  kCommand,      ///< another command (a jog, a track, a speed, self-commissioning)
  kLos,          ///< the pass ended
  kFailed,       ///< the follower failed (a fault, SGP4)
  kOff,          ///< track.recognise was turned off
};

/// A short name for the log, the API and /metrics ("departed", "stop", ...).
const char* recognition_end_name(RecognitionEnd why);

/// What the Controller recognised in a client's go-to stream, and when and
/// why it ended (GET /api/status "recognised", /metrics, the log).
struct Recognition {
  bool active = false;
  CommandSource source = kNoSource;  ///< the client whose stream it is
  tracking::TargetKind kind = tracking::TargetKind::kNone;
  char name[25] = {};         ///< "ISS (ZARYA)", "Sun", "Moon"
  std::uint32_t catalog = 0;  ///< NORAD number (satellites)
  std::int64_t began_utc_ms = 0;
  std::int64_t ended_utc_ms = 0;  ///< when it last ended (0: never)
  RecognitionEnd ended = RecognitionEnd::kNone;
  std::uint32_t gotos = 0;  ///< the client's go-tos followed since it began
  std::uint32_t begun = 0;  ///< recognitions since the controller started
  std::uint32_t endings = 0;
};

}  // namespace rotord
