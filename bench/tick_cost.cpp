#include "tick_cost.hpp"

#include <algorithm>
#include <chrono>
#include <memory>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord::bench {
namespace {

struct Rig {
  settings::Settings settings;
  sim::SimRotator sim;
  std::unique_ptr<Controller> controller;
  Millis now = 0;

  Rig() : sim(*sim::find_profile("g5500"), 7) {
    for (const auto& o : sim::find_profile("g5500")->overrides)
      settings.set(*settings::find(o.key), o.value);
    controller = std::make_unique<Controller>(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
    controller->begin(now);
    controller->go_to(300.0f, 60.0f);
  }
  // Sensors are sampled once; the tick alone is measured (the plant stands still).
  void ticks(long n) {
    for (long i = 0; i < n; ++i) {
      now += 10;
      controller->tick(now);
    }
  }
};

}  // namespace

Result run_tick_cost() {
  Rig rig;
  constexpr long kTicks = 20000;
  rig.ticks(1000);  // warm-up
  double best_ns = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    rig.ticks(kTicks);
    const auto t1 = std::chrono::steady_clock::now();
    best_ns = std::min(best_ns, std::chrono::duration<double, std::nano>(t1 - t0).count() / kTicks);
  }
  return {"footprint/tick_wall_ns",
          {{"ticks", static_cast<double>(kTicks)}},
          {{"ns_per_tick", best_ns}}};
}

void run_ticks_only(long ticks) {
  Rig rig;
  rig.ticks(ticks);
}

}  // namespace rotord::bench
