#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// Pointing error over simulated LEO passes (spherical Earth, circular
/// 420 km orbit, no Earth rotation), in virtual time:
/// the ideal speed-limited follower, and a Gpredict-style client talking to
/// rotord's rotctld session in process, driving the simulated g5500.
std::vector<Result> run_tracking_error();

}  // namespace rotord::bench
