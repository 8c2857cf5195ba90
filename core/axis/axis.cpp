#include "axis/axis.hpp"

#include <cmath>

#include "axis/sequences.hpp"
#include "motion/angles.hpp"

namespace rotord {
namespace {

float sign_of(Direction dir) {
  return static_cast<float>(static_cast<int>(dir));
}

Direction direction_of(float delta) {
  return delta >= 0.0f ? Direction::kCw : Direction::kCcw;
}

}  // namespace

Axis::Axis(AxisId id, const AxisIo& io) : id_(id), io_(io), tracker_(io_, cfg_) {}

void Axis::configure(const AxisConfig& cfg) {
  const bool first = !tracker_.fitted();
  const bool frame_moved = tracker_.configure(cfg);
  cfg_ = cfg;
  if (first) coast_s_ = cfg.coast_s;
  if (frame_moved && request_.kind == RequestKind::kGoto) request_.kind = RequestKind::kNone;
  if (frame_moved) rest_valid_ = false;  // an offset moved the position, not the wind
}

void Axis::begin(Millis now) {
  now_ = last_tick_ = now;
  out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  if (!tracker_.fitted()) latch_fault(AxisFault::kNoSensor);
  tracker_.read_switches();
  update_position(now);
  publish();
}

void Axis::update_position(Millis now) {
  tracker_.set_moving(state_ != AxisState::kIdle && state_ != AxisState::kFault);
  const PositionTracker::Update u = tracker_.update(now);
  if (u.fault != AxisFault::kNone && state_ != AxisState::kFault) latch_fault(u.fault);
  if (u.frame_changed && request_.kind == RequestKind::kGoto) request_.kind = RequestKind::kNone;
  if (u.frame_changed) rest_valid_ = false;  // a recalibration, not the wind
}

void Axis::shutdown() {
  seq_.cancel();
  out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  request_ = {};
  if (state_ != AxisState::kFault) state_ = AxisState::kIdle;
  publish();
}

Error Axis::go_to(float target_deg, bool paced) {
  if (state_ == AxisState::kFault) return Error::kFaulted;
  if (cfg_.continuous) target_deg = unwrap_near(target_deg, pos_deg());
  if (!cfg_.continuous && (target_deg < cfg_.min_deg || target_deg > cfg_.max_deg))
    return Error::kOutOfRange;
  if (request_.kind != RequestKind::kGoto || request_.target_deg != target_deg) {
    starts_this_request_ = 0;
    move_started_ = now_;
    move_distance_deg_ = std::fabs(target_deg - pos_deg());
  }
  request_ = {RequestKind::kGoto, target_deg, Direction::kNone, 0, paced};
  reholding_ = false;  // a command's go-to is no re-hold (rehold() sets it after)
  arrived_ = false;
  publish();
  return Error::kOk;
}

Error Axis::jog(Direction dir, Millis until) {
  if (state_ == AxisState::kFault) return Error::kFaulted;
  if (dir == Direction::kNone) {
    stop();
    return Error::kOk;
  }
  // A new jog is refused where the status already reports the limit (within
  // tolerance of the soft limit): a rotator that stopped 0.05 deg short of
  // its limit must not creep on because of sensor noise.
  const bool at_limit = dir == Direction::kCw ? status_.limit_cw : status_.limit_ccw;
  if (blocked(dir) || (at_limit && state_ == AxisState::kIdle)) return Error::kLimit;
  const bool new_jog = request_.kind != RequestKind::kJog || request_.dir != dir;
  request_ = {RequestKind::kJog, 0.0f, dir, until};
  reholding_ = false;
  if (new_jog) {
    move_started_ = now_;
    move_distance_deg_ = request_distance_deg();
  }
  arrived_ = false;
  publish();
  return Error::kOk;
}

void Axis::set_speed_pct(int pct) {
  if (pct == speed_pct_) return;
  speed_pct_ = pct;
  // A move slowed down on the way gets the time the rest of it needs.
  if (request_.kind != RequestKind::kNone) {
    move_started_ = now_;
    move_distance_deg_ = request_distance_deg();
  }
}

void Axis::stop() {
  request_ = {};
  reholding_ = false;
  publish();
}

void Axis::clear_fault() {
  if (state_ != AxisState::kFault) return;
  fault_ = AxisFault::kNone;
  state_ = AxisState::kIdle;
  stop_done_at_ = now_;
  tracker_.clear_errors();
  if (!tracker_.fitted()) latch_fault(AxisFault::kNoSensor);
  publish();
}

void Axis::emergency_stop() {
  if (fault_ == AxisFault::kEstop) return;
  latch_fault(AxisFault::kEstop);
  publish();
}

void Axis::latch_fault(AxisFault fault) {
  seq_.cancel();
  out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  request_ = {};
  reholding_ = false;
  fault_ = fault;
  state_ = AxisState::kFault;
  dir_ = Direction::kNone;
  reversing_ = false;
}

float Axis::stop_distance_deg() const {
  // Distance the antenna travels once a stop begins: a soft stop's run-on at
  // the slow speed, then the learned coast plus one tick of latency.
  const float speed_deg_s = std::fabs(status_.speed_deg_s);
  const float coast_deg = speed_deg_s * (coast_s_ + 0.01f);
  return soft_stop_run_on_ms() == 0 ? coast_deg : coast_deg + run_on_deg(speed_deg_s);
}

// How long a soft stop keeps the motor powered before the drive is cut
// (make_stop_sequence): a voltage-select drive also holds the creep supply
// for the direction relay's settle time, so its contacts break no current.
Millis Axis::soft_stop_run_on_ms() const {
  switch (cfg_.drive) {
    case DriveType::kRelay:
      return 0;
    case DriveType::kRelayTwoSpeed:
    case DriveType::kHBridge:
      return cfg_.soft_ms;
    case DriveType::kRelayVoltageSelect:
      return cfg_.soft_ms + cfg_.dir_settle_ms;
  }
  return 0;
}

// The run-on turns at the slow speed: the speed measured once the drive has
// run slow long enough for the motor to settle (the slow zone before a
// target), the configured slow rate (az.slow_speed_ratio) before that.
float Axis::run_on_deg(float speed_deg_s) const {
  // Called every tick while driving: no float work (soft float on the M0+)
  // for the usual drive without a soft stop.
  const Millis run_on_ms = soft_stop_run_on_ms();
  if (run_on_ms == 0) return 0.0f;
  constexpr Millis kSlowSettledMs = 1000;  // several motor time constants
  const bool settled_slow = now_ - fast_at_ >= kSlowSettledMs;
  const float slow_deg_s = expected_rate_deg_s(true);
  const float run_deg_s = settled_slow || speed_deg_s < slow_deg_s ? speed_deg_s : slow_deg_s;
  return run_deg_s * static_cast<float>(run_on_ms) / 1000.0f;
}

float Axis::commanded_duty(bool slow_zone) const {
  if (slow_zone) return cfg_.pwm_slow_duty;
  // SPEED 1..100 spans pwm_slow_duty (the lowest duty that moves, above the
  // dead band) to pwm_fast_duty, so every allowed speed turns the motor.
  const float pct = static_cast<float>(speed_pct_ - 1) / 99.0f;
  return cfg_.pwm_slow_duty + (cfg_.pwm_fast_duty - cfg_.pwm_slow_duty) * pct;
}

float Axis::expected_rate_deg_s(bool slow_zone) const {
  const bool slow = slow_zone || speed_pct_ <= 50;
  float ratio = 1.0f;
  switch (cfg_.drive) {
    case DriveType::kRelay:
      break;
    case DriveType::kRelayTwoSpeed:
    case DriveType::kRelayVoltageSelect:
      if (slow) ratio = cfg_.slow_speed_ratio;
      break;
    case DriveType::kHBridge: {
      // A DC motor's speed grows with the duty above its dead band (H-bridge
      // actuation).
      const float dead_band = cfg_.pwm_dead_band;
      ratio = (commanded_duty(slow_zone) - dead_band) / (1.0f - dead_band);
      break;
    }
  }
  // A slow duty set at or below the dead band never moves; the stall rule
  // reports that. The floor only keeps the allowance finite.
  constexpr float kSlowestRatio = 0.02f;
  if (!(ratio > kSlowestRatio)) ratio = kSlowestRatio;
  return cfg_.speed_deg_s * ratio;
}

Millis Axis::move_allowance_ms(float distance_deg) const {
  // Twice the expected travel at the commanded speed, so a rotator running at
  // half its rated speed (cold grease, low mains) still arrives, plus the
  // start and stop sequences of every allowed start; never less than the
  // configured timeout, which remains the allowance of short moves.
  const float slow_part_deg = distance_deg < cfg_.slow_zone_deg ? distance_deg : cfg_.slow_zone_deg;
  const float travel_s = (distance_deg - slow_part_deg) / expected_rate_deg_s(false) +
                         slow_part_deg / expected_rate_deg_s(true);
  const int brake_ms = cfg_.has_brake ? cfg_.brake_release_ms + cfg_.brake_engage_ms : 0;
  const int sequence_ms =
      cfg_.reverse_dead_ms + cfg_.min_dwell_ms + brake_ms + cfg_.dir_settle_ms + 2 * cfg_.soft_ms;
  constexpr float kMarginFactor = 2.0f;
  constexpr float kCoastAndSettleS = 10.0f;
  const float allowed_s = kMarginFactor * travel_s + kCoastAndSettleS +
                          static_cast<float>((kMaxCorrections + 1) * sequence_ms) / 1000.0f;
  const Millis allowed_ms = static_cast<Millis>(allowed_s * 1000.0f);
  return allowed_ms > cfg_.move_timeout_ms ? allowed_ms : cfg_.move_timeout_ms;
}

float Axis::request_distance_deg() const {
  switch (request_.kind) {
    case RequestKind::kGoto:
      return std::fabs(request_.target_deg - pos_deg());
    case RequestKind::kJog:
      // A jog may run to the end of the travel; an endless axis has no end,
      // and its jogs keep the configured timeout.
      if (cfg_.continuous) return 0.0f;
      return request_.dir == Direction::kCw ? cfg_.max_deg - pos_deg() : pos_deg() - cfg_.min_deg;
    case RequestKind::kNone:
      break;
  }
  return 0.0f;
}

bool Axis::blocked(Direction dir) const {
  if (dir == Direction::kCw) {
    if (tracker_.switch_cw()) return true;
    return !cfg_.continuous && pos_deg() + stop_distance_deg() >= cfg_.max_deg;
  }
  if (dir == Direction::kCcw) {
    if (tracker_.switch_ccw()) return true;
    return !cfg_.continuous && pos_deg() - stop_distance_deg() <= cfg_.min_deg;
  }
  return false;
}

Direction Axis::desired_direction() {
  switch (request_.kind) {
    case RequestKind::kNone:
      return Direction::kNone;
    case RequestKind::kJog:
      if (request_.until != 0 && now_ >= request_.until) {
        request_ = {};  // dead-man expired: the client went away
        return Direction::kNone;
      }
      if (blocked(request_.dir)) {
        request_ = {};
        return Direction::kNone;
      }
      return request_.dir;
    case RequestKind::kGoto:
      break;
  }
  const float err = request_.target_deg - pos_deg();
  const bool driving = state_ == AxisState::kStarting || state_ == AxisState::kMoving;
  if (driving) {
    const float remaining = err * sign_of(dir_);
    if (remaining < -cfg_.tolerance_deg) return direction_of(err);  // target behind: reverse
    if (remaining <= stop_distance_deg()) return Direction::kNone;  // cut now, coast in
    if (blocked(dir_)) return Direction::kNone;
    return dir_;
  }
  if (state_ == AxisState::kStopping) return Direction::kNone;  // judge once at rest
  if (std::fabs(err) <= cfg_.tolerance_deg) {
    request_ = {};
    arrived_ = true;
    return Direction::kNone;
  }
  if (starts_this_request_ > kMaxCorrections) {
    // No hunting: after the allowed corrections the axis stays where it is.
    request_ = {};
    return Direction::kNone;
  }
  const Direction dir = direction_of(err);
  if (blocked(dir)) {
    request_ = {};
    return Direction::kNone;
  }
  return dir;
}

void Axis::check_motion(Millis now) {
  if (std::fabs(pos_deg() - stall_ref_deg_) >= cfg_.stall_deg) {
    stall_ref_deg_ = pos_deg();
    stall_ref_t_ = now;
  } else if (now - stall_ref_t_ >= cfg_.stall_ms) {
    latch_fault(AxisFault::kStall);
    return;
  }
  // A frozen sensor against a jam: the drive is on, the axis was seen
  // turning at a good fraction of its speed, and then the raw value stopped
  // changing in one step, noise and all. A jammed or braked rotator slows
  // (the coast and the motor's inertia) and its sensor's noise goes on;
  // only a dead sensor repeats the very same value.
  if (tracker_.raw_changed_at() < drive_started_at_) return;  // judge this drive only
  const float was_deg_s = std::fabs(tracker_.speed_at_last_change());
  const float min_deg_s = 0.5f * expected_rate_deg_s(true);
  if (was_deg_s < min_deg_s || was_deg_s <= 0.0f) return;
  Millis wait_ms = static_cast<Millis>(3.0f * kCoarsestStepDeg * 1000.0f / was_deg_s);
  if (wait_ms < kSensorStuckMs) wait_ms = kSensorStuckMs;
  if (wait_ms < cfg_.stall_ms && now - tracker_.raw_changed_at() >= wait_ms)
    latch_fault(AxisFault::kSensorStuck);
}

void Axis::check_slip(Millis now) {
  // Only at rest with every output off (a relay rotator's brake is then
  // set): any motion now is the wind's, or gravity's, not the motor's.
  if (state_ != AxisState::kIdle || !tracker_.have_position() || cfg_.slip_deg <= 0.0f ||
      out_.any_on()) {
    rest_valid_ = false;
    slipping_ = false;
    return;
  }
  const float pos = pos_deg();
  if (!rest_valid_) {
    rest_valid_ = true;
    rest_deg_ = pos;
    return;
  }
  if (!slipping_) {
    if (std::fabs(pos - rest_deg_) < cfg_.slip_deg) return;
    slipping_ = true;
    ++slips_;
    slip_quiet_deg_ = pos;
    slip_quiet_at_ = now;
    if (cfg_.slip_fault) {
      latch_fault(AxisFault::kSlip);  // the fault wins over a re-hold
      return;
    }
    rehold(now);
    return;
  }
  // One slip, however far it goes: over once the position has settled.
  if (std::fabs(pos - slip_quiet_deg_) >= 0.5f * cfg_.slip_deg) {
    slip_quiet_deg_ = pos;
    slip_quiet_at_ = now;
  } else if (now - slip_quiet_at_ >= kSlipQuietMs) {
    slipping_ = false;
    rest_deg_ = pos;  // the new rest
  }
}

void Axis::rehold(Millis now) {
  // A brake holds the mast by itself; an axis with one never re-holds. A
  // command under way (even one waiting at rest) owns the axis.
  if (!cfg_.slip_rehold || cfg_.has_brake || !rehold_allowed_ ||
      request_.kind != RequestKind::kNone)
    return;
  // The oldest of the last kMaxReholds re-holds sits where the next one
  // goes in the ring: within the window, the wind wins and the slip is only
  // counted (a fixed ring: no heap in the tick).
  const std::size_t slot = reholds_ % kMaxReholds;
  if (reholds_ >= kMaxReholds && now - rehold_at_[slot] < kReholdWindowMs) {
    ++reholds_refused_;
    return;
  }
  const float target_deg = rest_deg_;
  if (go_to(target_deg) != Error::kOk) return;  // e.g. rested outside today's limits
  rehold_at_[slot] = now;
  ++reholds_;
  reholding_ = true;
  rehold_deg_ = target_deg;
}

void Axis::begin_start(Direction dir, Millis now) {
  dir_ = dir;
  reversing_ = false;
  state_ = AxisState::kStarting;
  duty_ = cfg_.pwm_slow_duty;
  ++starts_this_request_;
  ++moves_;
  stall_ref_t_ = now;
  stall_ref_deg_ = pos_deg();
  drive_started_at_ = now;
  fast_at_ = now;  // the motor's speed is not settled yet
  seq_.start(make_start_sequence(cfg_), dir, now);
  seq_.run(now, out_);
}

void Axis::begin_stop(bool hard, bool reversing, Millis now) {
  cut_deg_ = pos_deg();
  cut_speed_deg_s_ = status_.speed_deg_s;
  cut_run_on_deg_ = hard ? 0.0f : run_on_deg(std::fabs(cut_speed_deg_s_));
  reversing_ = reversing;
  state_ = reversing ? AxisState::kReversing : AxisState::kStopping;
  seq_.start(make_stop_sequence(cfg_, hard), dir_, now);
  seq_.run(now, out_);
  // The coast begins when a soft stop's run-on ends (a hard stop has none).
  drive_off_at_ = now + (hard ? 0 : soft_stop_run_on_ms());
}

void Axis::drive_moving(Millis now) {
  // Near the target every drive slows down; elsewhere relay drives follow the
  // WRC convention (speed 1-50 slow, 51-100 fast) and PWM scales the duty.
  const bool near_target = request_.kind == RequestKind::kGoto && !request_.paced &&
                           std::fabs(request_.target_deg - pos_deg()) <= cfg_.slow_zone_deg;
  const bool slow = near_target || speed_pct_ <= 50;
  switch (cfg_.drive) {
    case DriveType::kRelay:
      break;
    case DriveType::kRelayTwoSpeed:
      out_.set(OutputChannel::kSpeedFast, slow ? 0.0f : 1.0f);
      break;
    case DriveType::kRelayVoltageSelect:
      out_.set(OutputChannel::kVoltageFast, slow ? 0.0f : 1.0f);
      break;
    case DriveType::kHBridge: {
      // Inside the slow zone the duty tapers linearly from the cruise duty
      // to pwm_slow_duty at the target rather than dropping to it at the
      // zone's edge: the last degrees are still slow (the stop stays
      // accurate), the rest of the zone no longer crawls (bench: SPID
      // moves of 10-180 deg).
      float target = commanded_duty(false);
      if (near_target && cfg_.slow_zone_deg > 0.0f) {
        const float floor_duty = commanded_duty(true);
        const float frac = std::fabs(request_.target_deg - pos_deg()) / cfg_.slow_zone_deg;
        if (target > floor_duty) target = floor_duty + (target - floor_duty) * frac;
      }
      // Soft start: the duty slews at most full scale per soft_ms.
      float step = 1.0f;
      if (cfg_.soft_ms > 0)
        step = static_cast<float>(now - last_tick_) / static_cast<float>(cfg_.soft_ms);
      if (target > duty_) duty_ = (target - duty_ > step) ? duty_ + step : target;
      if (target < duty_) duty_ = (duty_ - target > step) ? duty_ - step : target;
      Sequencer::apply({StepTarget::kDirPwm, duty_, 0}, dir_, out_);
      break;
    }
  }
  // When the drive last ran fast: what a soft stop's run-on speed follows.
  if (soft_stop_run_on_ms() > 0) {
    const bool fast =
        cfg_.drive == DriveType::kHBridge ? duty_ > commanded_duty(true) + 0.01f : !slow;
    if (fast) fast_at_ = now;
  }
}

void Axis::finish_stop(Millis now) {
  // The coast learnt is what the travel shows beyond the modelled run-on.
  const float travelled = (pos_deg() - cut_deg_) * sign_of(dir_) - cut_run_on_deg_;
  const float speed = std::fabs(cut_speed_deg_s_);
  if (cfg_.coast_learn && speed > 0.5f && travelled > -0.5f) {
    float measured = travelled / speed - 0.01f;
    if (measured < 0.0f) measured = 0.0f;
    if (measured > 3.0f) measured = 3.0f;
    coast_s_ = 0.5f * coast_s_ + 0.5f * measured;
  }
  last_dir_ = dir_;
  dir_ = Direction::kNone;
  stop_done_at_ = now;
  state_ = AxisState::kIdle;
  if (request_.kind == RequestKind::kNone) reversing_ = false;
}

void Axis::tick(Millis now) {
  now_ = now;
  tracker_.read_switches();
  update_position(now);
  status_.speed_deg_s = tracker_.estimate_speed();

  start_held_ = false;
  if (state_ != AxisState::kFault) {
    const Direction want = desired_direction();
    switch (state_) {
      case AxisState::kIdle: {
        if (want == Direction::kNone) break;
        if (starts_held_ && request_.kind == RequestKind::kGoto) {
          // The starts ceiling: wait at rest; the move's time allowance
          // counts from the start it gets, not from the wait.
          start_held_ = true;
          move_started_ = now;
          move_distance_deg_ = std::fabs(request_.target_deg - pos_deg());
          break;
        }
        const Millis since_stop = now - stop_done_at_;
        const Millis wait = (want != last_dir_ && last_dir_ != Direction::kNone)
                                ? cfg_.reverse_dead_ms
                                : cfg_.min_dwell_ms;
        if (since_stop >= wait) begin_start(want, now);
        break;
      }
      case AxisState::kStarting:
      case AxisState::kMoving: {
        const bool hard = (dir_ == Direction::kCw && tracker_.switch_cw()) ||
                          (dir_ == Direction::kCcw && tracker_.switch_ccw());
        if (want != dir_) {
          begin_stop(hard, want != Direction::kNone, now);
          break;
        }
        if (state_ == AxisState::kStarting) {
          if (!seq_.run(now, out_)) state_ = AxisState::kMoving;
          break;
        }
        drive_moving(now);
        check_motion(now);
        if (state_ == AxisState::kMoving &&
            now - move_started_ >= move_allowance_ms(move_distance_deg_))
          latch_fault(AxisFault::kTimeout);
        break;
      }
      case AxisState::kStopping:
      case AxisState::kReversing: {
        if (seq_.run(now, out_)) break;
        // Drive is off; wait for the coast to end before judging the stop.
        const float settle_s = 4.0f * coast_s_ + 0.2f;
        const Millis settle_ms = static_cast<Millis>((settle_s > 3.0f ? 3.0f : settle_s) * 1000.0f);
        if (now - drive_off_at_ >= settle_ms) finish_stop(now);
        break;
      }
      case AxisState::kFault:
        break;
    }
  }

  check_slip(now);

  // Interlock, whatever the state: never both directions at once.
  if (out_.on(OutputChannel::kRelayCw) && out_.on(OutputChannel::kRelayCcw)) out_.all_off();
  if (out_.on(OutputChannel::kPwmCw) && out_.on(OutputChannel::kPwmCcw)) out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  last_tick_ = now;
  publish();
}

void Axis::publish() {
  status_.present = true;
  tracker_.publish(status_);
  status_.has_target = request_.kind == RequestKind::kGoto;
  status_.target_deg = request_.target_deg;
  if (cfg_.continuous && status_.has_target) status_.target_deg = wrap_360(request_.target_deg);
  status_.jogging = request_.kind == RequestKind::kJog;
  status_.arrived = arrived_;
  // After the stop of a reversal the axis waits out the dead time in idle;
  // report that wait as part of the reversal.
  status_.state = (state_ == AxisState::kIdle && reversing_) ? AxisState::kReversing : state_;
  status_.drive_dir = dir_;
  status_.fault = fault_;
  status_.coast_s = coast_s_;
  status_.moves = moves_;
  status_.slips = slips_;
  status_.slipping = slipping_;
  if (request_.kind != RequestKind::kGoto) reholding_ = false;  // arrived, or given up
  status_.reholds = reholds_;
  status_.rehold_deg = cfg_.continuous ? wrap_360(rehold_deg_) : rehold_deg_;
  status_.reholding = reholding_;
  status_.reholds_refused = reholds_refused_;
  status_.start_held = start_held_;
  status_.outputs = out_;
}

}  // namespace rotord
