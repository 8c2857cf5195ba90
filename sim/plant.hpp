#pragma once
#include <array>
#include <cstddef>

#include "axis/drive_outputs.hpp"
#include "sim/actuation.hpp"
#include "sim/fault_window.hpp"
#include "sim/plant_params.hpp"

namespace rotord::sim {

/// One rotator axis as the simulator models it: relay delay line,
/// first-order motor (powered) or coast (unpowered), brake, gear backlash
/// between the motor side phi and the output theta, hard end stops, and jam /
/// slip faults. Deterministic: no noise in the plant itself.
class AxisPlant {
 public:
  /// Longest internal integration step; longer step() calls are subdivided.
  static constexpr double kMaxStep_s = 0.001;

  explicit AxisPlant(const AxisPlantParams& params) : params_(params) {}

  /// Advances by dt_s with `outputs` held constant over the interval.
  void step(double dt_s, const DriveOutputs& outputs);

  /// Test set-up: puts the axis at rest at theta, backlash centred, no stored
  /// speed. Pending relay changes are kept (they model hardware in flight).
  void set_theta_deg(double theta_deg);

  // Faults, active from now for a duration (kForever_s for permanent).
  /// Mechanical jam: nothing turns; the motor stalls if powered.
  void jam(double duration_s) { jam_.start(t_s_, duration_s); }
  /// Slip / weak supply / wind: the powered target speed is scaled by load_factor.
  void slip(double load_factor, double duration_s) {
    slip_load_factor_ = load_factor;
    slip_.start(t_s_, duration_s);
  }
  /// Wind beating the brake (or the gear's hold, without one): while the
  /// motor is unpowered the antenna turns at `speed_deg_s`. A powered motor
  /// overrides it (its load is slip()'s business).
  void wind_slip(double speed_deg_s, double duration_s) {
    wind_slip_deg_s_ = speed_deg_s;
    wind_slip_.start(t_s_, duration_s);
  }
  void clear_faults() {
    jam_.clear();
    slip_.clear();
    wind_slip_.clear();
  }

  double theta_deg() const { return theta_deg_; }  ///< output angle (what sensors see)
  double phi_deg() const { return phi_deg_; }      ///< motor side, in output degrees
  double w_deg_s() const { return w_deg_s_; }      ///< motor-side speed
  bool powered() const { return applied_.powered; }
  bool brake_released() const { return applied_.brake_released; }
  /// Powered but prevented from turning (end stop, brake, jam): the current
  /// would be high, and a sane controller must notice and cut power.
  bool stalled() const { return stalled_; }
  bool jammed() const { return jam_.active(t_s_); }
  double time_s() const { return t_s_; }
  const AxisPlantParams& params() const { return params_; }

 private:
  struct PendingChange {
    double at_s;
    Actuation actuation;
  };
  // Relay operate time 10 ms and outputs changing at most once per step: a
  // handful of entries suffice; on overflow the oldest change is applied early.
  static constexpr std::size_t kDelayCapacity = 64;

  void push_change(const Actuation& a);
  void apply_due_changes();
  double time_to_next_change_s() const;
  void integrate(double h_s);
  void integrate_motor(double h_s, double target_deg_s, double tau_s);
  void integrate_brake(double h_s);
  void follow_backlash();
  void clamp_to_stops();
  void update_stalled();

  AxisPlantParams params_;
  double t_s_ = 0.0;
  double phi_deg_ = 0.0;
  double theta_deg_ = 0.0;
  double w_deg_s_ = 0.0;

  Actuation commanded_;  // last decoded outputs (before the delay)
  Actuation applied_;    // what the motor gets now (after the delay)
  std::array<PendingChange, kDelayCapacity> pending_{};
  std::size_t pending_head_ = 0;
  std::size_t pending_count_ = 0;

  FaultWindow jam_;
  FaultWindow slip_;
  double slip_load_factor_ = 1.0;
  FaultWindow wind_slip_;
  double wind_slip_deg_s_ = 0.0;
  bool stalled_ = false;
};

}  // namespace rotord::sim
