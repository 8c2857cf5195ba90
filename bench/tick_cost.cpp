#include "tick_cost.hpp"

#include <algorithm>
#include <chrono>
#include <memory>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord::bench {
namespace {

// A g5500 going to (300, 60): both axes start, move and stop within the run,
// so the ticks measured are a mix of moving and idle ones.
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
  // The plant is advanced either way; `control` adds the tick. The cost of a
  // tick is the difference between the two kinds of run.
  void steps(long n, bool control) {
    for (long i = 0; i < n; ++i) {
      now += 10;
      sim.advance_to(now);
      if (control) controller->tick(now);
    }
  }
};

double ns_per_step(long n, bool control) {
  double best_ns = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    Rig rig;
    const auto t0 = std::chrono::steady_clock::now();
    rig.steps(n, control);
    const auto t1 = std::chrono::steady_clock::now();
    best_ns = std::min(best_ns, std::chrono::duration<double, std::nano>(t1 - t0).count() /
                                    static_cast<double>(n));
  }
  return best_ns;
}

}  // namespace

Result run_tick_cost() {
  constexpr long kTicks = 6000;  // 60 s of virtual time
  const double with_ns = ns_per_step(kTicks, true);
  const double sim_ns = ns_per_step(kTicks, false);
  return {"footprint/tick_wall_ns",
          {{"ticks", static_cast<double>(kTicks)}},
          {{"ns_per_tick", std::max(0.0, with_ns - sim_ns)}}};
}

void run_steps_only(long ticks, bool control) {
  Rig rig;
  rig.steps(ticks, control);
}

}  // namespace rotord::bench
