#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// The tracking mode (issue 13) on the simulator, in virtual time: the
/// scenarios of tests/sim/scenario_tracking_test.cpp, each with its RMS and
/// maximum pointing error against the true target (great-circle; only the
/// elevation above 80 deg), the motor starts in the pass and the tick's cost
/// while tracking.
std::vector<Result> run_tracking_mode();

}  // namespace rotord::bench
