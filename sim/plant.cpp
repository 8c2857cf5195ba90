#include "sim/plant.hpp"

#include <algorithm>
#include <cmath>

namespace rotord::sim {

namespace {

// Event times are sums of many 1 ms steps; this absorbs the rounding.
constexpr double kTimeEps_s = 1e-9;

}  // namespace

void AxisPlant::step(double dt_s, const DriveOutputs& outputs) {
  const Actuation a = actuation_from(params_, outputs);
  if (!(a == commanded_)) {
    commanded_ = a;
    push_change(a);
  }
  double remaining_s = dt_s;
  while (remaining_s > kTimeEps_s) {
    apply_due_changes();
    // Split at relay events so the delay is exact even when it is not a
    // multiple of the step.
    double h_s = std::min(remaining_s, kMaxStep_s);
    const double to_change_s = time_to_next_change_s();
    if (to_change_s > kTimeEps_s && to_change_s < h_s) h_s = to_change_s;
    integrate(h_s);
    t_s_ += h_s;
    remaining_s -= h_s;
  }
  apply_due_changes();
  update_stalled();
}

void AxisPlant::set_theta_deg(double theta_deg) {
  theta_deg_ = theta_deg;
  if (!params_.continuous) {
    theta_deg_ = std::clamp(theta_deg_, params_.stop_min_deg, params_.stop_max_deg);
  }
  phi_deg_ = theta_deg_;
  w_deg_s_ = 0.0;
  update_stalled();
}

void AxisPlant::push_change(const Actuation& a) {
  if (params_.relay_delay_s <= 0.0) {
    // No delay line (H-bridge): the change takes effect at once.
    pending_count_ = 0;
    applied_ = a;
    return;
  }
  if (pending_count_ == kDelayCapacity) {
    applied_ = pending_[pending_head_].actuation;
    pending_head_ = (pending_head_ + 1) % kDelayCapacity;
    --pending_count_;
  }
  pending_[(pending_head_ + pending_count_) % kDelayCapacity] = {t_s_ + params_.relay_delay_s, a};
  ++pending_count_;
}

void AxisPlant::apply_due_changes() {
  while (pending_count_ > 0 && pending_[pending_head_].at_s <= t_s_ + kTimeEps_s) {
    applied_ = pending_[pending_head_].actuation;
    pending_head_ = (pending_head_ + 1) % kDelayCapacity;
    --pending_count_;
  }
}

double AxisPlant::time_to_next_change_s() const {
  if (pending_count_ == 0) return kMaxStep_s * 2.0;
  return pending_[pending_head_].at_s - t_s_;
}

void AxisPlant::integrate(double h_s) {
  if (jam_.active(t_s_)) {
    w_deg_s_ = 0.0;  // nothing moves; phi and theta hold
    return;
  }
  if (wind_slip_.active(t_s_) && !applied_.powered) {
    // The wind turns the antenna, which drags the gear train behind it
    // from the far flank of the play.
    const double half_deg = 0.5 * params_.backlash_deg;
    w_deg_s_ = 0.0;
    theta_deg_ += wind_slip_deg_s_ * h_s;
    if (theta_deg_ - phi_deg_ > half_deg) phi_deg_ = theta_deg_ - half_deg;
    if (theta_deg_ - phi_deg_ < -half_deg) phi_deg_ = theta_deg_ + half_deg;
  } else if (!applied_.brake_released) {
    integrate_brake(h_s);
  } else if (applied_.powered) {
    const double load = slip_.active(t_s_) ? slip_load_factor_ : 1.0;
    integrate_motor(h_s, applied_.target_ratio * params_.v_max_deg_s * load, params_.tau_m_s);
  } else {
    integrate_motor(h_s, 0.0, params_.tau_c_s);
  }
  clamp_to_stops();
}

// dw/dt = (w* - w) / tau, solved exactly over the step (input constant), so
// the result does not depend on the step size. A speed reversal inside the
// step is split at the zero crossing, so backlash is taken up at the true
// turning point.
void AxisPlant::integrate_motor(double h_s, double target_deg_s, double tau_s) {
  if (tau_s <= 0.0) {
    w_deg_s_ = target_deg_s;
    phi_deg_ += target_deg_s * h_s;
    follow_backlash();
    return;
  }
  const double w0 = w_deg_s_;
  double first_s = h_s;
  if (w0 * target_deg_s < 0.0) {
    const double cross_s = tau_s * std::log((w0 - target_deg_s) / -target_deg_s);
    if (cross_s > 0.0 && cross_s < h_s) first_s = cross_s;
  }
  const double decay = std::exp(-first_s / tau_s);
  w_deg_s_ = target_deg_s + (w0 - target_deg_s) * decay;
  phi_deg_ += target_deg_s * first_s + (w0 - target_deg_s) * tau_s * (1.0 - decay);
  follow_backlash();
  if (first_s < h_s) {
    w_deg_s_ = 0.0;  // exactly at the crossing
    integrate_motor(h_s - first_s, target_deg_s, tau_s);
  }
}

// A holding brake: constant deceleration to rest, then nothing turns. The
// motor, if powered, cannot overcome it (it stalls).
void AxisPlant::integrate_brake(double h_s) {
  const double w0 = w_deg_s_;
  const double speed = std::fabs(w0);
  const double decel = params_.brake_decel_deg_s2;
  const double sign = w0 < 0.0 ? -1.0 : 1.0;
  if (decel <= 0.0 || speed <= decel * h_s) {
    phi_deg_ += decel > 0.0 ? sign * speed * speed / (2.0 * decel) : 0.0;
    w_deg_s_ = 0.0;
  } else {
    phi_deg_ += w0 * h_s - sign * 0.5 * decel * h_s * h_s;
    w_deg_s_ = w0 - sign * decel * h_s;
  }
  follow_backlash();
}

// Backlash: the output only moves when the motor side pushes it from
// one flank of the gap.
void AxisPlant::follow_backlash() {
  const double half_deg = 0.5 * params_.backlash_deg;
  if (phi_deg_ - theta_deg_ > half_deg) {
    theta_deg_ = phi_deg_ - half_deg;
  } else if (phi_deg_ - theta_deg_ < -half_deg) {
    theta_deg_ = phi_deg_ + half_deg;
  }
}

void AxisPlant::clamp_to_stops() {
  if (params_.continuous) return;
  const double half_deg = 0.5 * params_.backlash_deg;
  if (theta_deg_ > params_.stop_max_deg) {
    theta_deg_ = params_.stop_max_deg;
    phi_deg_ = theta_deg_ + half_deg;
    w_deg_s_ = std::min(w_deg_s_, 0.0);
  } else if (theta_deg_ < params_.stop_min_deg) {
    theta_deg_ = params_.stop_min_deg;
    phi_deg_ = theta_deg_ - half_deg;
    w_deg_s_ = std::max(w_deg_s_, 0.0);
  }
}

void AxisPlant::update_stalled() {
  if (!applied_.powered) {
    stalled_ = false;
    return;
  }
  if (jam_.active(t_s_) || !applied_.brake_released) {
    stalled_ = true;
    return;
  }
  const bool pushing_max =
      applied_.target_ratio > 0.0 && !params_.continuous && theta_deg_ >= params_.stop_max_deg;
  const bool pushing_min =
      applied_.target_ratio < 0.0 && !params_.continuous && theta_deg_ <= params_.stop_min_deg;
  stalled_ = pushing_max || pushing_min;
}

}  // namespace rotord::sim
