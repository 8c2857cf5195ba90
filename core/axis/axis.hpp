#pragma once
#include <array>
#include <cstddef>

#include "axis/axis_config.hpp"
#include "axis/axis_io.hpp"
#include "axis/axis_status.hpp"
#include "axis/position_tracker.hpp"
#include "axis/sequencer.hpp"
#include "util/axis_id.hpp"
#include "util/error.hpp"
#include "util/time.hpp"

namespace rotord {

/// One rotator axis: runs the motion state machine (idle, starting, moving,
/// stopping, reversing, fault) on the position its PositionTracker reads, and
/// writes its drive outputs. The safety rules live here, so they hold whatever the command
/// source: never past a soft limit or an active limit switch, reversal only
/// through stop and a dead time, stall / sensor faults latch and stop.
///
/// No heap, no exceptions: everything is fixed-size members.
class Axis {
 public:
  /// Extra moves allowed to correct a go-to that ended outside tolerance.
  static constexpr int kMaxCorrections = 2;
  /// A reading exactly unchanged this long while driven at speed is a frozen
  /// sensor (SENSOR_STUCK), caught long before the stall rule (stall_ms).
  static constexpr Millis kSensorStuckMs = 600;
  /// The coarsest step a sensor's raw value moves in (a 10-bit MA3 code is
  /// 0.35 deg): below a speed that crosses three of them in kSensorStuckMs
  /// the wait grows so a slow axis is not taken for a frozen sensor.
  static constexpr float kCoarsestStepDeg = 0.5f;
  /// A slip is over once the position has stayed within half of slip.deg
  /// for this long; the next one counts again.
  static constexpr Millis kSlipQuietMs = 1000;
  /// slip.rehold must not fight a wind that keeps turning the mast: at most
  /// this many re-holds within kReholdWindowMs, then slips are only counted.
  static constexpr std::size_t kMaxReholds = 3;
  static constexpr Millis kReholdWindowMs = 10 * 60 * 1000;

  Axis(AxisId id, const AxisIo& io);
  // The tracker refers to this axis's io and configuration.
  Axis(const Axis&) = delete;
  Axis& operator=(const Axis&) = delete;

  void configure(const AxisConfig& cfg);
  /// All outputs off, first sensor reading.
  void begin(Millis now);
  void tick(Millis now);
  /// All outputs off at once (process exit, watchdog, brown-out).
  void shutdown();

  /// Go to an unwrapped position in the user frame (offset applied).
  /// `paced`: the tracker sets the speed (speed_pct) to the target's rate,
  /// so an H-bridge drive keeps that duty near the target instead of
  /// dropping to pwm_slow_duty in the slow zone.
  Error go_to(float target_deg, bool paced = false);
  /// Move in one direction until stop, a limit, or `until` (0 = no dead-man).
  Error jog(Direction dir, Millis until);
  void stop();
  /// All outputs off at once, no soft stop, and an ESTOP fault latched.
  void emergency_stop();
  void clear_fault();
  void set_speed_pct(int pct);
  /// The starts ceiling (care.max_starts_h, set by the controller each
  /// tick): while held, a go-to does not start the motor from rest (its
  /// target kept, started once allowed); jogs and STOP are never held.
  void hold_starts(bool held) { starts_held_ = held; }
  /// slip.rehold is allowed now (set by the controller each tick): not
  /// while a track is armed or self-commissioning runs, which own the axis.
  void allow_rehold(bool allowed) { rehold_allowed_ = allowed; }
  int speed_pct() const { return speed_pct_; }

  const AxisStatus& status() const { return status_; }
  const AxisConfig& config() const { return cfg_; }
  AxisId id() const { return id_; }

 private:
  enum class RequestKind : std::uint8_t { kNone, kGoto, kJog };
  struct Request {
    RequestKind kind = RequestKind::kNone;
    float target_deg = 0.0f;
    Direction dir = Direction::kNone;
    Millis until = 0;
    bool paced = false;
  };
  /// Reads the position; latches a sensor fault, voids a go-to whose frame
  /// moved.
  void update_position(Millis now);
  float pos_deg() const { return tracker_.position_deg(); }
  float stop_distance_deg() const;
  Millis soft_stop_run_on_ms() const;
  float run_on_deg(float speed_deg_s) const;
  float commanded_duty(bool slow_zone) const;
  float expected_rate_deg_s(bool slow_zone) const;
  Millis move_allowance_ms(float distance_deg) const;
  float request_distance_deg() const;
  bool blocked(Direction dir) const;
  Direction desired_direction();
  void begin_start(Direction dir, Millis now);
  void begin_stop(bool hard, bool reversing, Millis now);
  void drive_moving(Millis now);
  void finish_stop(Millis now);
  void latch_fault(AxisFault fault);
  /// The stall rule, and its sharper twin for a sensor that froze.
  void check_motion(Millis now);
  /// Uncommanded motion while the outputs are off (slip.deg).
  void check_slip(Millis now);
  /// After a slip on a brakeless axis (slip.rehold): a go-to back to the
  /// rest heading, within the limit of re-holds.
  void rehold(Millis now);
  void publish();

  AxisId id_;
  AxisIo io_;
  AxisConfig cfg_;
  PositionTracker tracker_;  // after io_ and cfg_, which it refers to

  AxisState state_ = AxisState::kIdle;
  AxisFault fault_ = AxisFault::kNone;
  Direction dir_ = Direction::kNone;       // direction driven, or stopping from
  Direction last_dir_ = Direction::kNone;  // direction of the last completed move
  Request request_;
  Sequencer seq_;
  DriveOutputs out_;
  int speed_pct_ = 50;
  float duty_ = 0.0f;

  Millis now_ = 0;
  Millis last_tick_ = 0;
  Millis stop_done_at_ = -1000000;  // when the motor was last cut
  Millis drive_off_at_ = 0;
  Millis move_started_ = 0;         // the request began (or its speed changed) then ...
  float move_distance_deg_ = 0.0f;  // ... with this far to go: sets its TIMEOUT allowance
  Millis stall_ref_t_ = 0;
  Millis drive_started_at_ = 0;  // the motor was last started then
  float stall_ref_deg_ = 0.0f;
  float cut_deg_ = 0.0f;
  float cut_speed_deg_s_ = 0.0f;
  float cut_run_on_deg_ = 0.0f;  // of that stop's travel, the modelled soft-stop run-on
  Millis fast_at_ = 0;           // the drive last ran faster than its slow speed (or started) then
  float coast_s_ = 0.15f;
  bool reversing_ = false;
  bool arrived_ = false;
  int starts_this_request_ = 0;
  std::uint32_t moves_ = 0;
  bool rest_valid_ = false;  // rest_deg_ is where the axis came to rest
  float rest_deg_ = 0.0f;
  bool slipping_ = false;
  float slip_quiet_deg_ = 0.0f;  // where a slip last moved to ...
  Millis slip_quiet_at_ = 0;     // ... and when
  std::uint32_t slips_ = 0;
  bool rehold_allowed_ = true;  // allow_rehold()
  bool reholding_ = false;      // the go-to under way is a re-hold
  float rehold_deg_ = 0.0f;
  std::uint32_t reholds_ = 0;
  std::uint32_t reholds_refused_ = 0;
  std::array<Millis, kMaxReholds> rehold_at_{};  // the last re-holds' times, a ring
  bool starts_held_ = false;                     // hold_starts()
  bool start_held_ = false;                      // a go-to waits for it now

  AxisStatus status_;
};

}  // namespace rotord
