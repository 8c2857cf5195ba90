#pragma once
// The set-up the tracking scenarios share (the continuity rule, recognising a
// client's pass): a rotator on the physics simulator at Boulder, its
// controller, and virtual time that starts at 2019-12-09 22:36:00 UTC, as the
// ISS's pass through north (iss_elements.hpp) begins.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>

#include "hal/wall_clock.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "tracking/julian.hpp"

namespace rotord::testing {

/// A profile's rotator at (az0, el0) with the station at Boulder, and a UTC
/// clock in step with virtual time. Counts the ticks a limit switch is hit
/// and the azimuth's extent while it runs.
class PassBench : public hal::WallClock {
 public:
  PassBench(const char* profile, double az0, double el0) : profile_(*sim::find_profile(profile)) {
    for (const auto& o : profile_.overrides) settings_.set(*settings::find(o.key), o.value);
    settings_.set(settings::Id::kStationLatDeg, 40.015);
    settings_.set(settings::Id::kStationLonDeg, -105.27);
    settings_.set(settings::Id::kStationAltM, 1655.0);
    sim_ = std::make_unique<sim::SimRotator>(profile_, 11);
    sim_->set_theta_deg(AxisId::kAz, az0);
    if (sim_->has_el()) sim_->set_theta_deg(AxisId::kEl, el0);
    EXPECT_TRUE(tracking::parse_utc("2019-12-09T22:36:00Z", utc0_));
  }
  PassBench(const PassBench&) = delete;
  PassBench& operator=(const PassBench&) = delete;
  ~PassBench() override = default;

  /// Builds the controller on the settings as they are now, lets `attach`
  /// hand it what a scenario adds (a clock, a TLE store), and begins it.
  void power_on() {
    controller_ =
        std::make_unique<Controller>(settings_, sim_->io(AxisId::kAz), sim_->io(AxisId::kEl));
    attach(*controller_);
    controller_->begin(now_);
  }
  std::optional<std::int64_t> unix_ms() const override { return utc0_ + now_; }
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      now_ += 10;
      sim_->advance_to(now_);
      controller_->tick(now_);
      const RotatorStatus s = controller_->status();
      if (s.az.switch_cw || s.az.switch_ccw || s.el.switch_cw || s.el.switch_ccw) ++limit_ticks_;
      const double az = theta(AxisId::kAz);
      min_az_ = std::fmin(min_az_, az);
      max_az_ = std::fmax(max_az_, az);
    }
  }
  /// Runs until both axes stand still and the azimuth has no target (at
  /// most 100 s of controller time).
  void settle() {
    for (int i = 0; i < 200; ++i) {
      run_ms(500);
      if (!controller_->status().moving() && !controller_->status().az.has_target) return;
    }
  }
  double theta(AxisId axis) const { return sim_->plant(axis).theta_deg(); }
  Controller& controller() { return *controller_; }
  settings::Settings& settings() { return settings_; }
  Millis now() const { return now_; }
  int limit_ticks() const { return limit_ticks_; }
  void reset_extent() { min_az_ = max_az_ = theta(AxisId::kAz); }
  double min_az() const { return min_az_; }
  double max_az() const { return max_az_; }

 protected:
  /// Called by power_on between building the controller and beginning it.
  virtual void attach(Controller&) {}

 private:
  const sim::Profile& profile_;
  settings::Settings settings_;
  std::int64_t utc0_ = 0;
  Millis now_ = 0;
  std::unique_ptr<sim::SimRotator> sim_;
  std::unique_ptr<Controller> controller_;
  int limit_ticks_ = 0;
  double min_az_ = 1e9, max_az_ = -1e9;
};

}  // namespace rotord::testing
