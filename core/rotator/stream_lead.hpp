#pragma once
#include <cstdint>

namespace rotord {

/// The lead rule for go-to streams (docs/tracking.md, "Fewer motor starts").
/// A tracker that sends where the satellite is now, each time the antenna is
/// off by more than its threshold (Gpredict 5 deg, the SatNOGS client 4,
/// SatDump none: then the axis's own tolerance), leaves the antenna trailing
/// by 0..threshold: one motor start per threshold of sky. Sending the axis a
/// lead ahead in the direction the stream moves, and holding it while the
/// target is within the band around it, centres the error on the target
/// instead: one start per two bands at the same RMS (a sawtooth of 0..b
/// and one of -b..b have the same RMS, b / sqrt(3)). Only the axes' own
/// moves change; what the client sent, the continuity rule and the frame it
/// reads back in do not. No heap, no state beyond a few floats per stream.
class StreamLead {
 public:
  /// How far ahead the axis is sent, as a fraction of the band: a little
  /// less than the band, so that a client with a threshold does not see
  /// the antenna beyond it (it would re-send every cycle).
  static constexpr float kLeadOfBand = 0.9f;
  /// The band as a fraction of the client's threshold as measured (the
  /// smallest error it ever sent a correction for).
  static constexpr float kBandOfThreshold = 0.9f;
  /// Same-direction steps in a row before an axis is led: one step gives a
  /// direction, two that agree a steady one (the elevation's turn at
  /// culmination is led again two steps after it).
  static constexpr int kSteadySteps = 2;
  /// The widest band: a client's threshold is a few degrees (Gpredict 5,
  /// the SatNOGS client 4); a stream of larger steps (a GS-232 timed list
  /// of 50 deg, the azimuth near the zenith) is led by no more than this.
  static constexpr float kMaxBandDeg = 6.0f;

  /// One axis of the stream: its last sent position and direction.
  struct Axis {
    bool have = false;
    float last_deg = 0.0f;
    int dir = 0;            ///< sign of the last step that moved
    int steady = 0;         ///< steps in a row in that direction
    float step_deg = 0.0f;  ///< the size of the last step
    /// Records a sent position (after the continuity rule: unwrapped).
    void note(float sent_deg);
    /// The direction when steady, else 0 (then the axis is not led).
    int steady_dir() const { return steady >= kSteadySteps ? dir : 0; }
  };

  /// What to do with one axis's go-to.
  struct Plan {
    bool hold = false;     ///< leave the axis where it stands
    float aim_deg = 0.0f;  ///< else: go here
  };

  /// Decides one axis: `sent_deg` what the client asked, `pos_deg` where
  /// the axis is, `dir` the stream's steady direction (0: literal),
  /// `at_rest` the axis stands with no target, `band_deg` the band,
  /// `min_deg`..`max_deg` the travel (the aim never leaves it).
  static Plan plan(float sent_deg, float pos_deg, int dir, bool at_rest, float band_deg,
                   float min_deg, float max_deg);

  /// A new stream: nothing known.
  void reset() { *this = StreamLead{}; }
  /// The client's error (in its frame, the larger of its axes) when it
  /// sent this go-to: the smallest seen is its threshold.
  void note_client_error(float error_deg) {
    if (error_deg < threshold_deg_) threshold_deg_ = error_deg;
  }
  /// The band for `axis` of tolerance `tolerance_deg`: the client's
  /// threshold as measured, but no more than the axis moved since the
  /// client's last command (the axis that did not make the client send
  /// moves little, and is led and held by as little), at most
  /// kMaxBandDeg, at least the tolerance.
  float band_deg(const Axis& axis, float tolerance_deg) const {
    const float moved = axis.step_deg < threshold_deg_ ? axis.step_deg : threshold_deg_;
    float b = kBandOfThreshold * moved;
    if (b > kMaxBandDeg) b = kMaxBandDeg;
    return b > tolerance_deg ? b : tolerance_deg;
  }
  Axis az;
  Axis el;
  /// Go-tos whose axes the rule led or held (GET /metrics).
  std::uint32_t led_count() const { return led_; }
  void count_led() { ++led_; }

 private:
  float threshold_deg_ = 1e9f;
  std::uint32_t led_ = 0;
};

}  // namespace rotord
