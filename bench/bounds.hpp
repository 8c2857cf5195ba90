#pragma once

namespace rotord::bench {

/// Plant parameters the time-optimal bounds depend on.
struct BoundPlant {
  double v_max_deg_s;
  double tau_m_s;  ///< powered speed lag; the trapezoid's acceleration is v / tau_m
  double tau_c_s;  ///< unpowered coast
  double brake_decel_deg_s2 = 0.0;  ///< holding brake's deceleration; 0 = no brake
};

/// Ideal trapezoid: D/v + v/a, or 2 sqrt(D/a) for short moves. The bound for
/// drives that can brake actively (H-bridge PWM).
double trapezoid_bound_s(const BoundPlant& p, double distance_deg);

/// Relay drive that can only cut power: run for t1, cut when the remaining
/// distance equals the coast w(t1) tau_c, then coast until the speed is 1 %
/// of v_max (the convention of data/time_optimal_bounds.csv).
double relay_coast_bound_s(const BoundPlant& p, double distance_deg);

/// Relay drive with a holding brake (Ham IV): run for t1, then the brake
/// stops the axis at a constant deceleration (sim/plant.cpp). Faster than
/// coasting, so the bell rotator is measured against this one.
double relay_brake_bound_s(const BoundPlant& p, double distance_deg);

/// Compares both formulas with every row of the reference CSV; returns the
/// largest absolute difference in seconds, or a negative value when the file
/// cannot be read.
double max_csv_bound_deviation_s(const char* csv_path, int* rows_checked);

}  // namespace rotord::bench
