#pragma once
#include <array>
#include <cstdint>
#include <optional>

#include "axis/axis_config.hpp"
#include "axis/axis_io.hpp"
#include "axis/axis_status.hpp"
#include "axis/sensor_registry.hpp"
#include "util/time.hpp"

namespace rotord {

/// Where one axis is: the fitted sensors and the configured one, the unwrap
/// of a single-turn reading onto the travel, the plausibility filter, the
/// speed estimate and the limit and overlap switches. It knows nothing of
/// motion: what a fault or a changed frame means for a move is the Axis's
/// business, so it reports them instead of acting on them.
///
/// What differs between sensor types is their row's business
/// (axis/sensor_registry.hpp), not this class's.
///
/// No heap: the sensors are fixed members, the history a fixed ring.
class PositionTracker {
 public:
  /// A reading may be missing this long before the sensor is declared lost.
  static constexpr Millis kSensorGraceMs = 250;
  /// Consecutive implausible readings tolerated (rejected) before a fault.
  static constexpr int kJumpRejectLimit = 5;
  /// The gate never closes below this fraction of the go-to tolerance (nor
  /// 1.5 x the sensor's resolution): a burst that gets through moves the
  /// position by little, and the tails of a filtered sensor's noise, which
  /// its mean absolute innovation underrates, still pass.
  static constexpr float kGateFloorOfTolerance = 0.5f;
  /// The gate opens to this many mean absolute innovations (~4 sigma).
  static constexpr float kGateNoiseFactor = 5.0f;
  /// Of the last 16 readings, this many off the gate is a burst: no reading
  /// is taken until it has passed (the position is carried on at the
  /// measured speed), and kJumpRejectLimit in a row latch SENSOR_JUMP.
  static constexpr int kBurstRejects = 4;
  /// The gate's allowance for a change of speed covers at most this long
  /// without a reading taken; beyond it only agreeing readings re-acquire.
  static constexpr Millis kGateMaxGapMs = 250;
  /// After the control loop itself was held up for longer (a busy machine)
  /// while the axis was driven, this many readings are allowed the whole
  /// wait: the one after it and, as a pot's median of three passes a step
  /// on one reading late, the two that follow.
  static constexpr int kStallReadings = 3;

  /// What a reading told the axis beyond the position itself.
  struct Update {
    AxisFault fault = AxisFault::kNone;  ///< a sensor fault to latch
    bool frame_changed =
        false;  ///< a recalibration moved the frame: a go-to in the old one is void
  };

  /// `cfg` is the axis's configuration, read at every update.
  PositionTracker(const AxisIo& io, const AxisConfig& cfg);

  /// Fits the sensors for `next` (the axis's configuration becomes `next`
  /// right after). Returns true when the reported position moved by an
  /// offset change (a go-to in the old frame is void).
  bool configure(const AxisConfig& next);
  /// The configured sensor is fitted.
  bool fitted() const { return sensor_ != nullptr; }

  void read_switches();
  /// Whether the motor turns the axis now (driven or coasting): only then
  /// is the position carried on at the measured speed past a rejected
  /// reading; at rest the measured "speed" is the sensor's noise.
  void set_moving(bool moving) { moving_ = moving; }
  Update update(Millis now);
  /// Degrees per second over the last ~300 ms of readings; 0 until the
  /// readings span 100 ms.
  float estimate_speed() const;
  /// A fault was cleared: count sensor trouble afresh.
  void clear_errors();

  /// How long the sensor's raw value has been exactly the same (a live
  /// sensor's noise or motion changes it), and the speed measured when it
  /// last changed: the Axis tells a frozen sensor from a jam with them.
  Millis raw_changed_at() const { return raw_changed_at_; }
  float speed_at_last_change() const { return speed_at_change_deg_s_; }
  /// Readings the gate rejected since start (bursts, spikes).
  std::uint32_t gated_readings() const { return gated_; }

  bool have_position() const { return have_pos_; }
  float position_deg() const { return pos_deg_; }
  bool switch_cw() const { return sw_cw_; }
  bool switch_ccw() const { return sw_ccw_; }
  bool t1() const { return t1_; }
  bool t2() const { return t2_; }

  /// The position, sensor and switch fields of the status.
  void publish(AxisStatus& status) const;

 private:
  struct Sample {
    Millis t = 0;
    float deg = 0.0f;
  };

  float initial_unwrap(float sensor_deg) const;
  /// The robust filter: true when `pos` (user frame) at `now` fits the
  /// axis's measured motion; learns the sensor's noise from the readings
  /// it takes.
  bool plausible(float pos, Millis now, float speed_deg_s);
  /// A reading was not taken: carries the position on at the measured speed
  /// (the motor keeps turning while the sensor is unreadable) and counts it.
  AxisFault reject(Millis now, float speed_deg_s);
  void note_raw(float raw, Millis now, float speed_deg_s);
  /// Counts the time since the last update(): a stall of the loop.
  void note_loop_gap(Millis now);
  float reported_position_deg() const;

  const AxisIo& io_;
  const AxisConfig& cfg_;
  SensorSlots sensors_;                                     // every type whose input is wired
  std::array<PositionSensor*, kSensorTypeCount> fitted_{};  // by type; nullptr: not wired
  PositionSensor* sensor_ = nullptr;

  bool have_pos_ = false;
  float pos_deg_ = 0.0f;     // user frame
  float sensor_deg_ = 0.0f;  // unwrapped, sensor frame
  float raw_ = 0.0f;
  Millis bad_since_ = -1;
  int jump_rejects_ = 0;
  bool recalibrated_ = false;        // the calibration changed: accept the next reading
  bool answered_ = false;            // the last read got a sample from the sensor
  Millis pos_t_ = 0;                 // when pos_deg_ was read
  bool read_before_ = false;         // update() ran before ...
  Millis read_t_ = 0;                // ... last at this time
  Millis stall_ms_ = 0;              // the last stall of the loop (kGateMaxGapMs or more)
  int stall_readings_left_ = 0;      // readings still allowed stall_ms_
  float noise_abs_deg_ = 0.0f;       // mean |innovation| of the readings taken
  std::uint16_t rejected_bits_ = 0;  // the last 16 readings, 1 = not taken
  float resolution_deg_ = 0.1f;
  bool resync_ = false;  // a fault was reset: take the next reading
  bool moving_ = false;
  std::uint32_t gated_ = 0;
  Millis raw_changed_at_ = 0;
  float speed_at_change_deg_s_ = 0.0f;
  std::array<Sample, 32> history_{};
  int history_head_ = 0;
  int history_count_ = 0;

  bool sw_cw_ = false, sw_ccw_ = false, t1_ = false, t2_ = false;
};

}  // namespace rotord
