#include "rotator/axis_events.hpp"

#include <cmath>
#include <cstdio>

namespace rotord {

void AxisEvents::begin(const RotatorStatus& status) {
  slips_ = {status.az.slips, status.el.slips};
  faults_ = {status.az.fault, status.el.fault};
  held_ = {status.az.start_held, status.el.start_held};
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
  return false;
}

}  // namespace rotord
