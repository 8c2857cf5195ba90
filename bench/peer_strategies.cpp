#include "peer_strategies.hpp"

#include <algorithm>
#include <cmath>

namespace rotord::bench {

DriveOutputs drive_outputs(sim::DriveKind drive, bool has_brake, int dir, double duty) {
  DriveOutputs out;
  if (dir == 0) return out;
  if (drive == sim::DriveKind::kHBridge) {
    out.set(dir > 0 ? OutputChannel::kPwmCw : OutputChannel::kPwmCcw, static_cast<float>(duty));
    return out;
  }
  out.set(dir > 0 ? OutputChannel::kRelayCw : OutputChannel::kRelayCcw, 1.0f);
  if (has_brake) out.set(OutputChannel::kBrake, 1.0f);  // released while driving
  return out;
}

DriveOutputs WrcTwoSpeed::step(double error_deg) {
  const double abs_err = std::fabs(error_deg);
  const int want_dir = error_deg > 0 ? 1 : -1;
  if (driving_ && (abs_err <= kStopWithinDeg || want_dir != dir_)) {
    driving_ = false;  // stop; a passed target is approached again after a restart
  } else if (!driving_ && abs_err > restart_deg_) {
    driving_ = true;
    dir_ = want_dir;
  }
  if (!driving_) return {};
  double duty = 1.0;
  if (abs_err <= kSlowWithinDeg) {
    duty = kSlowDuty;
  } else if (abs_err < kFastBeyondDeg) {
    duty = kSlowDuty +
           (1.0 - kSlowDuty) * (abs_err - kSlowWithinDeg) / (kFastBeyondDeg - kSlowWithinDeg);
  }
  return drive_outputs(drive_, has_brake_, dir_, duty);
}

DriveOutputs PicoRotorSlowZone::step(double error_deg) {
  const double abs_err = std::fabs(error_deg);
  if (abs_err <= 1.0) return {};
  const double duty = abs_err < 5.0 ? 0.30 + (0.50 - 0.30) * abs_err / 5.0 : 1.0;
  return drive_outputs(drive_, has_brake_, error_deg > 0 ? 1 : -1, duty);
}

}  // namespace rotord::bench
