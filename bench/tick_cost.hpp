#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// Wall-clock cost of one 100 Hz control tick on this machine (both axes,
/// g5500, mid-move). A benchmark number only; the repeatable count is the
/// callgrind one (bench/run.py footprint).
Result run_tick_cost();

/// Runs `ticks` steps of the plant, each with a control tick when `control`
/// is set, for callgrind's instruction count: rotord_bench --ticks N minus
/// rotord_bench --sim-only N, over N, is what one tick executes.
void run_steps_only(long ticks, bool control);

}  // namespace rotord::bench
