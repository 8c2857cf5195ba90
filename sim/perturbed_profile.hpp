#pragma once
#include <cstdint>

#include "sim/profiles.hpp"

namespace rotord::sim {

/// A profile whose azimuth plant is not the one its settings describe: the
/// unknown rotator self-commissioning (docs/commissioning.md) has to measure.
/// Shared by the commissioning scenario tests and the commissioning bench so
/// that both meet the same plants for the same seed.
struct PerturbedProfile {
  Profile profile;  ///< `overrides` still the nominal profile's settings
  /// The CW and CCW outputs wired the wrong way round (see SwappedWiring).
  bool swap_wires = false;
};

/// Speed +/-30 %, coast +/-30 %, backlash +/-50 %, the pot's offset (about
/// 0.15 V +/-50 %) and span (+/-8 %) unless `perturb_pot` is false, and the
/// CW/CCW outputs swapped in about 40 % of the seeds.
PerturbedProfile perturbed_profile(const Profile& nominal, std::uint64_t seed,
                                   bool perturb_pot = true);

}  // namespace rotord::sim
