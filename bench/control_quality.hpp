#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// Go-to quality in virtual time for rotord and the peer strategies on every
/// simulator profile: the move set, a move through the overlap and a reversal
/// in mid-move. One Result per (controller, profile, scenario).
std::vector<Result> run_control_quality();

}  // namespace rotord::bench
