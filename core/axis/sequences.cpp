#include "axis/sequences.hpp"

namespace rotord {

Sequence make_start_sequence(const AxisConfig& cfg) {
  Sequence seq;
  if (cfg.has_brake) seq.add(StepTarget::kBrake, 1.0f, cfg.brake_release_ms);
  switch (cfg.drive) {
    case DriveType::kRelay:
      seq.add(StepTarget::kDirRelay, 1.0f, 0);
      break;
    case DriveType::kRelayTwoSpeed:
      // Start slow; a soft start holds the slow speed for soft_ms.
      seq.add(StepTarget::kSpeedFast, 0.0f, cfg.dir_settle_ms);
      seq.add(StepTarget::kDirRelay, 1.0f, cfg.soft_ms);
      break;
    case DriveType::kRelayVoltageSelect:
      // The direction relay switches while only the creep supply is selected;
      // the fast supply comes later (moving state) so the contacts never make
      // or break the high-voltage current.
      seq.add(StepTarget::kVoltageFast, 0.0f, 0);
      seq.add(StepTarget::kDirRelay, 1.0f,
              cfg.dir_settle_ms > cfg.soft_ms ? cfg.dir_settle_ms : cfg.soft_ms);
      break;
    case DriveType::kHBridge:
      seq.add(StepTarget::kDirPwm, cfg.pwm_slow_duty, 0);
      break;
  }
  return seq;
}

Sequence make_stop_sequence(const AxisConfig& cfg, bool hard) {
  Sequence seq;
  const int soft_ms = hard ? 0 : cfg.soft_ms;
  switch (cfg.drive) {
    case DriveType::kRelay:
      seq.add(StepTarget::kDirRelay, 0.0f, 0);
      break;
    case DriveType::kRelayTwoSpeed:
      if (soft_ms > 0) seq.add(StepTarget::kSpeedFast, 0.0f, soft_ms);
      seq.add(StepTarget::kDirRelay, 0.0f, 0);
      seq.add(StepTarget::kSpeedFast, 0.0f, 0);
      break;
    case DriveType::kRelayVoltageSelect:
      if (soft_ms > 0) seq.add(StepTarget::kVoltageFast, 0.0f, soft_ms);
      seq.add(StepTarget::kVoltageFast, 0.0f, hard ? 0 : cfg.dir_settle_ms);
      seq.add(StepTarget::kDirRelay, 0.0f, 0);
      break;
    case DriveType::kHBridge:
      if (soft_ms > 0) seq.add(StepTarget::kDirPwm, cfg.pwm_slow_duty, soft_ms);
      seq.add(StepTarget::kDirPwm, 0.0f, 0);
      break;
  }
  if (cfg.has_brake) {
    // Let the antenna coast to rest before the brake drops (K3NG waits 3 s).
    seq.add(StepTarget::kBrake, 1.0f, cfg.brake_engage_ms);
    seq.add(StepTarget::kBrake, 0.0f, 0);
  }
  return seq;
}

}  // namespace rotord
