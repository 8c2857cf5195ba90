#pragma once
#include "axis/axis.hpp"

namespace rotord {

/// What following learns about one axis while it drives it: the lag from a
/// command to motion and the full-speed slew speed (docs/tracking.md).
struct AxisFollow {
  float lag_ms = 300.0f;     ///< command to motion
  float speed_deg_s = 6.0f;  ///< full-speed slew
  Millis commanded_at = 0;   ///< a start from rest was commanded then ...
  bool awaiting_motion = false;
  float peak_speed_deg_s = 0;  ///< ... the fastest seen during this move
  bool was_moving = false;
  bool full_speed_move = false;
  /// How far ahead of the target the axis is sent, in bands (0.8: it leads
  /// by about a band, waits for the target to pass and starts once it is a
  /// band behind, one start per ~2 bands; 0: it stops on the target and
  /// starts once it is a band away, one start per band). Benchmarks set 0
  /// to measure what the lead saves (bench/tracking_mode.cpp).
  float lead_bands = 0.8f;
};

/// Updates the lag and speed from what the axis did this tick.
void learn_axis(AxisFollow& f, const Axis& axis, Millis now);

/// Drives one axis along a moving target: `want_now` where it is now,
/// `want_lead` where it will be after the axis's lag, `rate_deg_s` its rate.
/// Aims a band ahead so relays start once per two bands (never sooner than
/// min_dwell_ms), keeps a running motor's target ahead (a fast target is
/// followed at the plant's speed), paces H-bridge drives to the rate
/// (`hurry`: full speed). Used by the tracking mode and by following an
/// external tracker's implied rate.
void follow_axis(Axis& axis, AxisFollow& f, float want_now, float want_lead, float rate_deg_s,
                 Millis now, bool hurry);

}  // namespace rotord
