#include "rotator/axis_events.hpp"

#include <cmath>
#include <cstdio>

namespace rotord {

void AxisEvents::begin(const RotatorStatus& status) {
  slips_ = {status.az.slips, status.el.slips};
  reholds_ = {status.az.reholds, status.el.reholds};
  reholds_refused_ = {status.az.reholds_refused, status.el.reholds_refused};
  faults_ = {status.az.fault, status.el.fault};
  held_ = {status.az.start_held, status.el.start_held};
  wind_state_ = status.wind_state;
  wind_rejected_ = status.wind_rejected;
}

bool AxisEvents::wind_event(const RotatorStatus& s, char* line, std::size_t capacity) {
  if (s.wind_rejected != wind_rejected_) {
    wind_rejected_ = s.wind_rejected;
    if (wind_rejected_ >= wind_rejected_told_at_) {
      while (wind_rejected_told_at_ <= wind_rejected_ && wind_rejected_told_at_ < 1000000000u)
        wind_rejected_told_at_ *= 10;
      std::snprintf(line, capacity,
                    "wind: a reading ignored (garbage, negative, too high or stale: see "
                    "/api/status wind.rejected); %lu since start",
                    static_cast<unsigned long>(wind_rejected_));
      return true;
    }
  }
  if (s.wind_state == wind_state_) return false;
  const care::WindState was = wind_state_;
  wind_state_ = s.wind_state;
  using care::WindState;
  if (s.wind_state == WindState::kStowed) {
    std::snprintf(line, capacity,
                  was == WindState::kOverride
                      ? "wind: the operator's override ended at %.1f m/s: stowing again"
                      : "wind: %.1f m/s held for wind.hold_s: stowing, other moves refused until "
                        "calm",
                  static_cast<double>(s.wind_speed_mps));
    return true;
  }
  if (s.wind_state == WindState::kOverride) {
    std::snprintf(line, capacity, "wind: the stow overridden by an operator (wind.override_min)");
    return true;
  }
  if (s.wind_state == WindState::kCalm &&
      (was == WindState::kStowed || was == WindState::kOverride)) {
    std::snprintf(line, capacity,
                  "wind: calm (%.1f m/s) for wind.calm_min: the stow ends, moves obeyed again",
                  static_cast<double>(s.wind_speed_mps));
    return true;
  }
  return false;
}

bool AxisEvents::next(const RotatorStatus& status, char* line, std::size_t capacity) {
  const AxisStatus* axes[2] = {&status.az, &status.el};
  const char* names[2] = {"az", "el"};
  for (std::size_t n = 0; n < 2; ++n) {
    const AxisStatus& a = *axes[n];
    if (!a.present) continue;
    if (a.slips != slips_[n]) {
      slips_[n] = a.slips;
      std::snprintf(line, capacity,
                    "%s: slip: moved slip.deg at rest with the outputs off, now at %.1f deg "
                    "(%lu slips since start)",
                    names[n], static_cast<double>(a.position_deg),
                    static_cast<unsigned long>(a.slips));
      return true;
    }
    if (a.reholds != reholds_[n]) {
      reholds_[n] = a.reholds;
      std::snprintf(line, capacity, "%s: slip: re-holding %.1f deg (%lu re-holds since start)",
                    names[n], static_cast<double>(a.rehold_deg),
                    static_cast<unsigned long>(a.reholds));
      return true;
    }
    if (a.reholds_refused != reholds_refused_[n]) {
      reholds_refused_[n] = a.reholds_refused;
      std::snprintf(line, capacity,
                    "%s: slip: not re-holding: %u re-holds within %u min (slip.rehold's limit); "
                    "the wind wins, slips are only counted",
                    names[n], static_cast<unsigned>(Axis::kMaxReholds),
                    static_cast<unsigned>(Axis::kReholdWindowMs / 60000));
      return true;
    }
    if (a.fault != faults_[n]) {
      faults_[n] = a.fault;
      if (a.fault == AxisFault::kNone) continue;  // a reset: the command said so
      std::snprintf(line, capacity, "%s: fault %s latched at %.1f deg", names[n],
                    axis_fault_name(a.fault), static_cast<double>(a.position_deg));
      return true;
    }
    if (a.start_held != held_[n]) {
      held_[n] = a.start_held;
      if (!a.start_held) continue;
      std::snprintf(line, capacity,
                    "%s: starts ceiling (care.max_starts_h) reached: a go-to waits, its tolerance "
                    "widened to %.1f deg",
                    names[n], static_cast<double>(std::fabs(a.target_deg - a.position_deg)));
      return true;
    }
  }
  return wind_event(status, line, capacity);
}

}  // namespace rotord
