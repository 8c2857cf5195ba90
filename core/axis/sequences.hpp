#pragma once
#include "axis/axis_config.hpp"
#include "axis/sequencer.hpp"

namespace rotord {

/// The start sequence of a drive: brake release, direction relay, soft start.
/// Ends with the motor driven at slow speed; the moving state takes over.
Sequence make_start_sequence(const AxisConfig& cfg);

/// The stop sequence: soft stop, drive off, coast, brake engage. `hard` skips
/// the soft-stop step (limit switch, fault, emergency stop).
Sequence make_stop_sequence(const AxisConfig& cfg, bool hard);

}  // namespace rotord
