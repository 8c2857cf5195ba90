#pragma once
// The set-up the tracking scenarios share (the continuity rule, recognising a
// client's pass): a rotator on the physics simulator at Boulder, its
// controller, and virtual time that starts at 2019-12-09 22:36:00 UTC, as the
// ISS's pass through north (iss_elements.hpp) begins.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "hal/wall_clock.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "sim_bench.hpp"
#include "tracking/julian.hpp"

namespace rotord::testing {

/// A profile's rotator at (az0, el0) with the station at Boulder, and a UTC
/// clock in step with virtual time. Counts the ticks a limit switch is hit
/// and the azimuth's extent while it runs.
class PassBench : public SimBench, public hal::WallClock {
 public:
  PassBench(const char* profile, double az0, double el0)
      : SimBench(*sim::find_profile(profile), 11, az0, el0) {
    set_station(40.015, -105.27, 1655.0);
    EXPECT_TRUE(tracking::parse_utc("2019-12-09T22:36:00Z", utc0_));
  }

  std::optional<std::int64_t> unix_ms() const override { return utc0_ + now(); }
  /// Runs until both axes stand still and the azimuth has no target (at
  /// most 100 s of controller time).
  void settle() {
    for (int i = 0; i < 200; ++i) {
      run_ms(500);
      if (!status().moving() && !status().az.has_target) return;
    }
  }
  int limit_ticks() const { return limit_ticks_; }
  void reset_extent() { min_az_ = max_az_ = theta(AxisId::kAz); }
  double min_az() const { return min_az_; }
  double max_az() const { return max_az_; }

 private:
  void on_tick() override {
    if (on_a_limit_switch(status())) ++limit_ticks_;
    const double az = theta(AxisId::kAz);
    min_az_ = std::fmin(min_az_, az);
    max_az_ = std::fmax(max_az_, az);
  }

  std::int64_t utc0_ = 0;
  int limit_ticks_ = 0;
  double min_az_ = 1e9, max_az_ = -1e9;
};

}  // namespace rotord::testing
