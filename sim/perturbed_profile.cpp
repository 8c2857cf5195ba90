#include "sim/perturbed_profile.hpp"

#include "sim/rng.hpp"

namespace rotord::sim {
namespace {

double perturb(Rng& rng, double value, double fraction) {
  return value * (1.0 + fraction * (2.0 * rng.uniform() - 1.0));
}

}  // namespace

PerturbedProfile perturbed_profile(const Profile& nominal, std::uint64_t seed, bool perturb_pot) {
  PerturbedProfile out{nominal, false};
  Rng rng(seed * 7919 + 13);
  auto& plant = out.profile.az.plant;
  plant.v_max_deg_s = perturb(rng, plant.v_max_deg_s, 0.3);
  plant.tau_c_s = perturb(rng, plant.tau_c_s, 0.3);
  plant.backlash_deg = perturb(rng, plant.backlash_deg, 0.5);
  auto& pot = out.profile.az.pot;
  // Drawn whether or not they are used, so that a seed's swap is the same.
  const double v_min = perturb(rng, pot.v_at_min_v + 0.1, 0.5);  // offset
  const double v_max = perturb(rng, pot.v_at_max_v, 0.08);       // span
  if (perturb_pot) {
    pot.v_at_min_v = v_min;
    pot.v_at_max_v = v_max;
  }
  out.swap_wires = rng.uniform() < 0.4;
  return out;
}

}  // namespace rotord::sim
