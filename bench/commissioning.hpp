#pragma once
#include <vector>

#include "results.hpp"

namespace rotord::bench {

/// Self-commissioning on every simulator profile, the nominal plant and
/// three perturbed by seed (sim/perturbed_profile.hpp): the rotator time it
/// takes, and the control rows (run_control_quality's move set, rotord only)
/// with the settings it proposes against the hand-tuned profile on the
/// same plant. Rows commissioning/<profile>/seed<N>[/<scenario>].
std::vector<Result> run_commissioning();

}  // namespace rotord::bench
