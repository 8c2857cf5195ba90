#include "rotator/axis_follower.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord {
namespace {

float clampf(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

}  // namespace

void learn_axis(AxisFollow& f, const Axis& axis, Millis now) {
  const AxisStatus& s = axis.status();
  const AxisConfig& c = axis.config();
  const bool moving = s.state == AxisState::kStarting || s.state == AxisState::kMoving;
  const float speed = std::fabs(s.speed_deg_s);
  if (f.awaiting_motion) {
    const float threshold = std::fmin(0.5f, 0.2f * c.speed_deg_s);
    if (speed >= threshold) {
      const float sample = clampf(static_cast<float>(now - f.commanded_at), 0.0f, 5000.0f);
      f.lag_ms = 0.7f * f.lag_ms + 0.3f * sample;
      f.awaiting_motion = false;
    } else if (!moving && !s.has_target) {
      f.awaiting_motion = false;  // arrived without moving (within tolerance)
    }
  }
  if (moving) {
    if (!f.was_moving) {
      f.commanded_at = f.awaiting_motion ? f.commanded_at : now;
      f.peak_speed_deg_s = 0.0f;
      f.full_speed_move = axis.speed_pct() >= 100;
    }
    f.peak_speed_deg_s = std::fmax(f.peak_speed_deg_s, speed);
    f.was_moving = true;
  } else if (f.was_moving) {
    // A long move at full speed tells the slew speed (for pre-positioning).
    if (f.full_speed_move && f.peak_speed_deg_s > 0.5f * c.speed_deg_s)
      f.speed_deg_s = 0.7f * f.speed_deg_s + 0.3f * f.peak_speed_deg_s;
    f.was_moving = false;
  }
}

void follow_axis(Axis& axis, AxisFollow& f, float want_now, float want_lead, float rate_deg_s,
                 Millis now, bool hurry) {
  const AxisStatus& s = axis.status();
  const AxisConfig& c = axis.config();
  if (!s.position_valid || s.fault != AxisFault::kNone) return;
  const float pos = s.position_deg;
  if (c.continuous) {
    // An endless axis reads 0..360: compare on the turn nearest the antenna.
    want_now = unwrap_near(want_now, pos);
    want_lead = unwrap_near(want_lead, pos);
  }
  // The band the antenna may lag or lead by: its tolerance, or wider when the
  // target is fast and the relays must rest min_dwell_ms between starts.
  const float rate = std::fabs(rate_deg_s);
  const float band =
      std::fmax(c.tolerance_deg, 0.5f * rate * static_cast<float>(c.min_dwell_ms) / 1000.0f);
  const float sign = rate_deg_s > 0.02f ? 1.0f : (rate_deg_s < -0.02f ? -1.0f : 0.0f);
  // Aim ahead of where the target will be once the axis moves, so that the
  // antenna leads by about the band and then waits for the target to pass:
  // one start per 2 x band of the target's travel, not one per tolerance.
  float aim = want_lead + sign * f.lead_bands * band;
  if (!c.continuous) aim = clampf(aim, c.min_deg + 0.2f, c.max_deg - 0.2f);
  if (c.drive == DriveType::kHBridge) {
    // Follow at the target's pace: the duty for 1.3 x its rate plus the
    // error, full speed when far behind (pre-positioning, the zenith).
    const float err = std::fabs(want_now - pos);
    int pct = 100;
    if (!hurry && err < 5.0f) {
      const float want_rate = 1.3f * rate + 0.5f * err;
      const float ratio = clampf(want_rate / c.speed_deg_s, 0.0f, 1.0f);
      const float duty = c.pwm_dead_band + ratio * (1.0f - c.pwm_dead_band);
      const float span = c.pwm_fast_duty - c.pwm_slow_duty;
      const float f_pct = span > 0.01f ? 1.0f + 99.0f * (duty - c.pwm_slow_duty) / span : 100.0f;
      pct = static_cast<int>(clampf(f_pct, 1.0f, 100.0f) + 0.5f);
    }
    axis.set_speed_pct(pct);
  } else if (axis.speed_pct() != 100) {
    axis.set_speed_pct(100);
  }
  const bool paced = c.drive == DriveType::kHBridge;
  const bool driving = s.state == AxisState::kStarting || s.state == AxisState::kMoving;
  if (!driving && !s.has_target && s.state == AxisState::kIdle) {
    if (std::fabs(want_lead - pos) > band) {
      axis.go_to(aim, paced);
      f.commanded_at = now;
      f.awaiting_motion = true;
    }
    return;
  }
  if (driving && s.has_target) {
    // Keep the target ahead while the motor runs: a fast target is followed
    // at the plant's speed instead of stop-and-go.
    const float target = c.continuous ? unwrap_near(s.target_deg, pos) : s.target_deg;
    const float drive_sign = s.drive_dir == Direction::kCw ? 1.0f : -1.0f;
    if (std::fabs(aim - target) > 0.1f && (aim - pos) * drive_sign > 0.0f) axis.go_to(aim, paced);
  }
}

}  // namespace rotord
