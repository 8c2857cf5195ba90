#pragma once
#include <array>
#include <optional>

#include "axis/axis_config.hpp"
#include "axis/axis_io.hpp"
#include "axis/axis_status.hpp"
#include "sensors/ma3_sensor.hpp"
#include "sensors/mag_sensor.hpp"
#include "sensors/pot_sensor.hpp"
#include "util/time.hpp"

namespace rotord {

/// Where one axis is: the fitted sensors and the configured one, the unwrap
/// of a single-turn reading onto the travel, the plausibility filter, the
/// speed estimate and the limit and overlap switches. It knows nothing of
/// motion: what a fault or a changed frame means for a move is the Axis's
/// business, so it reports them instead of acting on them.
///
/// No heap: the sensors are fixed members, the history a fixed ring.
class PositionTracker {
 public:
  /// A reading may be missing this long before the sensor is declared lost.
  static constexpr Millis kSensorGraceMs = 250;
  /// Consecutive implausible readings tolerated (rejected) before a fault.
  static constexpr int kJumpRejectLimit = 5;

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
  Update update(Millis now);
  /// Degrees per second over the last ~300 ms of readings.
  float estimate_speed() const;
  /// A fault was cleared: count sensor trouble afresh.
  void clear_errors();

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
  float reported_position_deg() const;

  const AxisIo& io_;
  const AxisConfig& cfg_;
  std::optional<PotSensor> pot_;
  std::optional<Ma3Sensor> ma3_;
  std::optional<MagSensor> mag_;
  PositionSensor* sensor_ = nullptr;

  bool have_pos_ = false;
  float pos_deg_ = 0.0f;     // user frame
  float sensor_deg_ = 0.0f;  // unwrapped, sensor frame
  float raw_ = 0.0f;
  Millis bad_since_ = -1;
  int jump_rejects_ = 0;
  bool recalibrated_ = false;  // the calibration changed: accept the next reading
  bool mag_answered_ = false;  // the last read got a sample from the chip
  std::array<Sample, 32> history_{};
  int history_head_ = 0;
  int history_count_ = 0;

  bool sw_cw_ = false, sw_ccw_ = false, t1_ = false, t2_ = false;
};

}  // namespace rotord
