#include "commissioning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "control_quality.hpp"
#include "rotator/controller.hpp"
#include "sim/adc_scale.hpp"
#include "sim/perturbed_profile.hpp"
#include "sim/sim_rotator.hpp"
#include "sim/swapped_wiring.hpp"

namespace rotord::bench {
namespace {

constexpr Millis kTickMs = 10;
constexpr Millis kRunLimitMs = 60LL * 60 * 1000;
// Seed 0 is the nominal plant (the one the profile's settings were made
// for, outputs the right way round); 1..3 the perturbed plants of the
// scenario tests (tests/sim/scenario_commissioning_test.cpp).
constexpr std::uint64_t kSeeds = 7;
// The bench's settle band (control_quality.cpp): a final error beyond it
// is a miss.
constexpr double kBandDeg = 1.0;

settings::Settings profile_settings(const sim::Profile& p) {
  settings::Settings s;
  for (const auto& o : p.overrides) s.set(*settings::find(o.key), o.value);
  return s;
}

/// The hand-tuned profile on this plant: the profile's settings with the
/// pot calibrated right (as an owner reading the pot at both ends would),
/// so that the comparison is of the tuning, not of a wrong calibration.
settings::Settings hand_tuned(const sim::Profile& p) {
  settings::Settings s = profile_settings(p);
  const sim::AxisProfile& a = p.az;
  if (a.sensor == SensorType::kPot) {
    s.set(settings::Id::kAzPotCalLoCounts, sim::adc_counts_exact(a.pot.v_at_min_v));
    s.set(settings::Id::kAzPotCalLoDeg, a.min_deg);
    s.set(settings::Id::kAzPotCalHiCounts, sim::adc_counts_exact(a.pot.v_at_max_v));
    s.set(settings::Id::kAzPotCalHiDeg, a.max_deg);
    s.set(settings::Id::kAzPotCalMidPoints, 0);
  }
  return s;
}

struct Commissioned {
  bool ok = false;
  const char* why = "";
  double rotator_s = 0;
  bool swapped = false;
  double speed_err_pct = 0;
  double coast_err_pct = 0;
  settings::Settings proposed;
};

/// Self-commissioning as the owner runs it: start, accept the swap if it
/// proposes one (then the wiring is right) and run again, accept.
Commissioned commission(const sim::PerturbedProfile& pp, std::uint64_t seed) {
  const sim::Profile& p = pp.profile;
  Commissioned c;
  settings::Settings s = profile_settings(p);
  sim::SimRotator rotator(p, seed);
  rotator.set_theta_deg(AxisId::kAz, 0.5 * (p.az.min_deg + p.az.max_deg) + 17.0);
  AxisIo az = rotator.io(AxisId::kAz);
  sim::SwappedWiring wiring(az.drive);
  wiring.swapped = pp.swap_wires;
  az.drive = &wiring;
  Controller controller(s, az, rotator.io(AxisId::kEl));
  Millis now = 0;
  controller.begin(now);
  Commissioning::Request r;
  r.ccw_stop_deg = static_cast<float>(p.az.limit_ccw_deg);
  r.cw_stop_deg = static_cast<float>(p.az.limit_cw_deg);
  const Commissioning& run = controller.commissioning();
  for (int attempt = 0; attempt < 2; ++attempt) {
    const char* why = "";
    if (controller.commission(r, &why) != Error::kOk) {
      c.why = why;
      return c;
    }
    const Millis t0 = now;
    while (run.running() && now - t0 < kRunLimitMs) {
      now += kTickMs;
      rotator.advance_to(now);
      controller.tick(now);
    }
    c.rotator_s += static_cast<double>(now - t0) / 1000.0;
    if (run.state() != Commissioning::State::kDone) {
      c.why = run.reason();
      return c;
    }
    if (!run.proposes_swap()) break;
    c.swapped = true;
    if (controller.accept_commissioning().error != Error::kOk) {
      c.why = "the swap was refused";
      return c;
    }
    wiring.swapped = false;  // the pins are swapped: the wiring is right now
  }
  const auto& m = run.measured();
  const auto& plant = p.az.plant;
  c.speed_err_pct = 100.0 * std::fabs(m.fast_deg_s - plant.v_max_deg_s) / plant.v_max_deg_s;
  const double coast_true_s = plant.tau_c_s + plant.relay_delay_s;
  c.coast_err_pct = 100.0 * std::fabs(m.coast_s - coast_true_s) / coast_true_s;
  if (controller.accept_commissioning().error != Error::kOk) {
    c.why = "the proposal was refused";
    return c;
  }
  c.proposed = s;
  c.ok = true;
  return c;
}

}  // namespace

std::vector<Result> run_commissioning() {
  std::vector<Result> results;
  for (const sim::Profile* nominal : sim::all_profiles()) {
    for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
      const sim::PerturbedProfile pp = seed == 0 ? sim::PerturbedProfile{*nominal, false}
                                                 : sim::perturbed_profile(*nominal, seed);
      const std::string base =
          std::string("commissioning/") + nominal->name + "/seed" + std::to_string(seed);
      const Commissioned c = commission(pp, seed);
      if (!c.ok) {
        std::fprintf(stderr, "bench: commissioning %s failed: %s\n", base.c_str(), c.why);
        results.push_back({base, {{"seed", static_cast<double>(seed)}}, {{"failed", 1.0}}});
        continue;
      }
      const auto hand = rotord_move_quality(pp.profile, hand_tuned(pp.profile));
      const auto prop = rotord_move_quality(pp.profile, c.proposed);
      int worse = 0;
      double worst_eff_delta = 0, hand_max_err = 0, prop_max_err = 0;
      for (std::size_t n = 0; n < hand.size(); ++n) {
        const MoveQuality& h = hand[n];
        const MoveQuality& q = prop[n];
        // Worse: efficiency lower by more than the table's rounding (0.01),
        // a motor start more, or a final error outside the settle band.
        // (Errors inside the band are compared as the max of the run.)
        const bool is_worse = q.efficiency < h.efficiency - 0.01 || q.corrections > h.corrections ||
                              (q.final_error_deg > kBandDeg && h.final_error_deg <= kBandDeg);
        worse += is_worse ? 1 : 0;
        worst_eff_delta = std::min(worst_eff_delta, q.efficiency - h.efficiency);
        hand_max_err = std::max(hand_max_err, h.final_error_deg);
        prop_max_err = std::max(prop_max_err, q.final_error_deg);
        results.push_back({base + "/" + h.scenario,
                           {{"seed", static_cast<double>(seed)}, {"bound_s", h.bound_s}},
                           {{"hand_efficiency", h.efficiency},
                            {"proposed_efficiency", q.efficiency},
                            {"hand_final_error_deg", h.final_error_deg},
                            {"proposed_final_error_deg", q.final_error_deg},
                            {"hand_corrections", static_cast<double>(h.corrections)},
                            {"proposed_corrections", static_cast<double>(q.corrections)},
                            {"proposed_worse", is_worse ? 1.0 : 0.0}}});
      }
      const settings::Settings& s = c.proposed;
      results.push_back({base,
                         {{"seed", static_cast<double>(seed)}, {"swapped", c.swapped ? 1.0 : 0.0}},
                         {{"rotator_s", c.rotator_s},
                          {"speed_error_pct", c.speed_err_pct},
                          {"coast_error_pct", c.coast_err_pct},
                          {"proposed_tolerance_deg", s.get(settings::Id::kAzToleranceDeg)},
                          {"proposed_slow_zone_deg", s.get(settings::Id::kAzSlowZoneDeg)},
                          {"proposed_coast_s", s.get(settings::Id::kAzCoastS)},
                          {"rows", static_cast<double>(hand.size())},
                          {"rows_worse", static_cast<double>(worse)},
                          {"worst_efficiency_change", worst_eff_delta},
                          {"hand_max_error_deg", hand_max_err},
                          {"proposed_max_error_deg", prop_max_err}}});
    }
  }
  return results;
}

}  // namespace rotord::bench
