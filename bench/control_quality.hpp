#pragma once
#include <string>
#include <vector>

#include "results.hpp"
#include "settings/settings.hpp"
#include "sim/profiles.hpp"

namespace rotord::bench {

/// Go-to quality in virtual time for rotord and the peer strategies on every
/// simulator profile: the move set, a move through the overlap and a reversal
/// in mid-move. One Result per (controller, profile, scenario).
std::vector<Result> run_control_quality();

/// rotord alone on the same scenarios, on `profile`'s plant (perturbed or
/// not) with `settings` in force: how well a set of settings drives a plant.
struct MoveQuality {
  std::string scenario;  ///< as in the control rows: move_90, reversal_180, ...
  double bound_s;
  double settle_s;  ///< NaN: never settled within 1 deg
  double efficiency;
  double final_error_deg;
  int corrections;
};
std::vector<MoveQuality> rotord_move_quality(const sim::Profile& profile,
                                             const settings::Settings& settings);

}  // namespace rotord::bench
