#pragma once
// What the whole-controller scenarios share: a profile's rotator on the
// physics simulator, its controller, and virtual time run in the 10 ms ticks
// of the daemon's loop. Each scenario derives and keeps its own per-tick
// measurement (limit switches, relays, the pointing error) in on_tick().
#include <memory>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord::testing {

class SimBench {
 public:
  /// The profile's rotator (a copy, so that a variation of a built-in one can
  /// be handed in) at (az0, el0), with the profile's settings applied; the
  /// seed picks the simulator's sensor noise.
  SimBench(const sim::Profile& profile, unsigned seed, double az0_deg, double el0_deg)
      : profile_(profile) {
    for (const auto& o : profile_.overrides) settings_.set(*settings::find(o.key), o.value);
    sim_ = std::make_unique<sim::SimRotator>(profile_, seed);
    sim_->set_theta_deg(AxisId::kAz, az0_deg);
    if (sim_->has_el()) sim_->set_theta_deg(AxisId::kEl, el0_deg);
  }
  SimBench(const SimBench&) = delete;
  SimBench& operator=(const SimBench&) = delete;
  virtual ~SimBench() = default;

  /// The station the controller computes the sky from.
  void set_station(double lat_deg, double lon_deg, double alt_m) {
    settings_.set(settings::Id::kStationLatDeg, lat_deg);
    settings_.set(settings::Id::kStationLonDeg, lon_deg);
    settings_.set(settings::Id::kStationAltM, alt_m);
  }

  /// Builds the controller on the settings as they are now (again after a
  /// power cut: a new controller on the same, unmoved rotator), lets
  /// `attach` hand it what a scenario adds (a clock, a TLE store), and
  /// begins it.
  void power_on() {
    controller_ =
        std::make_unique<Controller>(settings_, sim_->io(AxisId::kAz), sim_->io(AxisId::kEl));
    attach(*controller_);
    controller_->begin(now_);
  }

  /// Runs the controller for `ms` in ticks of 10 ms, measuring after each.
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      now_ += 10;
      sim_->advance_to(now_);
      controller_->tick(now_);
      on_tick();
    }
  }

  double theta(AxisId axis) const { return sim_->plant(axis).theta_deg(); }
  RotatorStatus status() const { return controller_->status(); }
  Controller& controller() { return *controller_; }
  const Controller& controller() const { return *controller_; }
  settings::Settings& settings() { return settings_; }
  sim::SimRotator& sim() { return *sim_; }
  const sim::SimRotator& sim() const { return *sim_; }
  Millis now() const { return now_; }

  /// Whether any axis stands on one of its limit switches.
  static bool on_a_limit_switch(const RotatorStatus& s) {
    return s.az.switch_cw || s.az.switch_ccw || s.el.switch_cw || s.el.switch_ccw;
  }

 protected:
  /// Called by power_on between building the controller and beginning it.
  virtual void attach(Controller&) {}
  /// Called after every tick of run_ms: a scenario's measurement.
  virtual void on_tick() {}

 private:
  const sim::Profile profile_;
  settings::Settings settings_;
  std::unique_ptr<sim::SimRotator> sim_;
  std::unique_ptr<Controller> controller_;
  Millis now_ = 0;
};

}  // namespace rotord::testing
