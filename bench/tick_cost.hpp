#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// Wall-clock cost of one 100 Hz control tick on this machine (both axes,
/// g5500, mid-move). A benchmark number only; the repeatable count is the
/// callgrind one (bench/run.py footprint).
Result run_tick_cost();

/// Runs `ticks` control ticks with nothing else around them, for callgrind's
/// instruction count (rotord_bench --ticks N).
void run_ticks_only(long ticks);

}  // namespace rotord::bench
