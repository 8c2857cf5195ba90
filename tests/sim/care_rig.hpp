#pragma once
// A controller on a simulated rotator in virtual time, for the scenarios of
// docs/care.md (sensor faults, slips).
#include <memory>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord {

class Rig {
 public:
  explicit Rig(const char* profile, double az0_deg, std::uint64_t seed = 11)
      : profile_(*sim::find_profile(profile)) {
    for (const auto& o : profile_.overrides) settings_.set(*settings::find(o.key), o.value);
    sim_ = std::make_unique<sim::SimRotator>(profile_, seed);
    sim_->set_theta_deg(AxisId::kAz, az0_deg);
    if (sim_->has_el()) sim_->set_theta_deg(AxisId::kEl, 10.0);
    controller_ =
        std::make_unique<Controller>(settings_, sim_->io(AxisId::kAz), sim_->io(AxisId::kEl));
    controller_->begin(now_);
  }

  void tick() {
    now_ += 10;
    sim_->advance_to(now_);
    controller_->tick(now_);
  }
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) tick();
  }
  /// Runs until the azimuth latches a fault (or limit_ms); the time it took.
  Millis run_until_fault(Millis limit_ms) {
    for (Millis t = 0; t < limit_ms; t += 10) {
      tick();
      if (az().fault != AxisFault::kNone) return t + 10;
    }
    return -1;
  }

  const AxisStatus& az() {
    status_ = controller_->status();
    return status_.az;
  }
  double theta() const { return sim_->plant(AxisId::kAz).theta_deg(); }
  Controller& controller() { return *controller_; }
  settings::Settings& settings() { return settings_; }
  sim::SimRotator& sim() { return *sim_; }
  Millis now() const { return now_; }

 private:
  const sim::Profile profile_;
  settings::Settings settings_;
  std::unique_ptr<sim::SimRotator> sim_;
  std::unique_ptr<Controller> controller_;
  RotatorStatus status_;
  Millis now_ = 0;
};

}  // namespace rotord
