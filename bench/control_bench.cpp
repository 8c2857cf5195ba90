// Control-tick cost and control quality on the simulator. Benchmarks print
// numbers; no test asserts on them.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string_view>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord {
namespace {

struct Rig {
  settings::Settings settings;
  sim::SimRotator sim;
  std::unique_ptr<Controller> controller;
  Millis now = 0;

  static settings::Settings with_profile(const sim::Profile& p) {
    settings::Settings s;
    for (const auto& o : p.overrides) s.set(*settings::find(o.key), o.value);
    return s;
  }
  explicit Rig(std::string_view profile)
      : settings(with_profile(*sim::find_profile(profile))), sim(*sim::find_profile(profile), 7) {
    power_on();
  }
  void power_on() {
    controller = std::make_unique<Controller>(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
    controller->begin(now);
  }
  void tick() {
    now += 10;
    sim.advance_to(now);
    controller->tick(now);
  }
};

// Cost of one 100 Hz control tick alone (sensor reads, both axis FSMs).
void BM_ControlTick(benchmark::State& state) {
  Rig rig("g5500");
  rig.controller->go_to(300.0f, 60.0f);
  for (auto _ : state) {
    rig.now += 10;
    rig.controller->tick(rig.now);
  }
}
BENCHMARK(BM_ControlTick);

// Move quality: a go-to on each profile, reporting the time to settle, the
// final error and the number of motor starts (1 = no correction).
void BM_GotoQuality(benchmark::State& state, const char* profile, float from_deg, float to_deg) {
  double settle_s = 0, error_deg = 0, starts = 0;
  for (auto _ : state) {
    Rig rig(profile);
    rig.sim.set_theta_deg(AxisId::kAz, from_deg);
    rig.power_on();
    rig.controller->go_to(to_deg, std::nullopt, AzTarget::kUnwrapped);
    Millis settled_at = 0;
    for (int n = 0; n < 30000; ++n) {
      rig.tick();
      const auto s = rig.controller->status();
      if (!s.az.has_target && s.az.state == AxisState::kIdle) {
        settled_at = rig.now;
        break;
      }
    }
    settle_s = static_cast<double>(settled_at) / 1000.0;
    error_deg = std::fabs(rig.sim.plant(AxisId::kAz).theta_deg() - to_deg);
    starts = rig.controller->status().az.moves;
  }
  // Lower bound on the move time: the whole distance at the plant's top speed.
  const double v_max_deg_s = sim::find_profile(profile)->az.plant.v_max_deg_s;
  const double bound_s = std::fabs(to_deg - from_deg) / v_max_deg_s;
  state.counters["settle_s"] = settle_s;
  state.counters["speed_bound_s"] = bound_s;
  state.counters["efficiency"] = settle_s > 0 ? bound_s / settle_s : 0.0;
  state.counters["final_error_deg"] = error_deg;
  state.counters["motor_starts"] = starts;
}
BENCHMARK_CAPTURE(BM_GotoQuality, g5500_180deg, "g5500", 100.0f, 280.0f)->Iterations(1);
BENCHMARK_CAPTURE(BM_GotoQuality, g5500_10deg, "g5500", 100.0f, 110.0f)->Iterations(1);
BENCHMARK_CAPTURE(BM_GotoQuality, ham4_180deg, "ham4", 100.0f, 280.0f)->Iterations(1);
BENCHMARK_CAPTURE(BM_GotoQuality, spid_180deg, "spid", 100.0f, 280.0f)->Iterations(1);

}  // namespace
}  // namespace rotord

BENCHMARK_MAIN();
