#pragma once
#include <limits>

namespace rotord::sim {

/// Duration that never ends, for permanent faults.
inline constexpr double kForever_s = std::numeric_limits<double>::infinity();

/// A fault that is active from the moment it is injected for a duration, in
/// simulated seconds. Times are the plant's own clock, never the wall clock.
class FaultWindow {
 public:
  void start(double now_s, double duration_s) { until_s_ = now_s + duration_s; }
  void clear() { until_s_ = -std::numeric_limits<double>::infinity(); }
  /// The margin absorbs the rounding of time summed from 1 ms steps, so a
  /// 1 s fault injected at t = 2 s is over at the step that ends at t = 3 s.
  bool active(double now_s) const { return now_s < until_s_ - 1e-9; }

 private:
  double until_s_ = -std::numeric_limits<double>::infinity();
};

}  // namespace rotord::sim
