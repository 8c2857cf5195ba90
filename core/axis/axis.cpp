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

/// True when the active sensor's calibration differs: the same shaft position
/// then reads as another angle, in one step.
bool sensor_frame_changed(const AxisConfig& a, const AxisConfig& b) {
  if (a.sensor != b.sensor) return false;  // a new sensor starts afresh anyway
  switch (b.sensor) {
    case SensorType::kPot:
      if (a.pot_cal.count != b.pot_cal.count) return true;
      for (std::size_t n = 0; n < static_cast<std::size_t>(b.pot_cal.count); ++n)
        if (a.pot_cal.points[n].counts != b.pot_cal.points[n].counts ||
            a.pot_cal.points[n].deg != b.pot_cal.points[n].deg)
          return true;
      return false;
    case SensorType::kMa3:
      return a.ma3_zero_deg != b.ma3_zero_deg || a.ma3_reverse != b.ma3_reverse ||
             a.ma3_bits != b.ma3_bits;
    case SensorType::kMag:
      return !(a.mag_cal == b.mag_cal) || a.mag_chip != b.mag_chip;
  }
  return false;
}

bool active(hal::DigitalIn* in) {
  return in != nullptr && in->active();
}

}  // namespace

Axis::Axis(AxisId id, const AxisIo& io) : id_(id), io_(io) {
  if (io_.pot) pot_.emplace(*io_.pot);
  if (io_.ma3) ma3_.emplace(*io_.ma3);
  if (io_.i2c) mag_.emplace(*io_.i2c);
}

void Axis::configure(const AxisConfig& cfg) {
  const float offset_change = cfg.offset_deg - cfg_.offset_deg;
  const bool first = sensor_ == nullptr;
  // A recalibration (web page, GS-232 O/F) moves the reading in one step. The
  // next reading is taken as it comes, not rejected as an implausible jump:
  // that fault would latch, and no reset could clear it.
  if (!first && have_pos_ && sensor_frame_changed(cfg_, cfg)) recalibrated_ = true;
  cfg_ = cfg;
  if (pot_) {
    pot_->configure(cfg.pot_cal, cfg.pot_filter);
  }
  if (ma3_) ma3_->configure(cfg.ma3_bits, cfg.ma3_zero_deg, cfg.ma3_reverse);
  if (mag_) mag_->configure(cfg.mag_chip, cfg.mag_cal, cfg.mag_lowpass_ms);
  PositionSensor* chosen = nullptr;
  if (cfg.sensor == SensorType::kPot && pot_) chosen = &*pot_;
  if (cfg.sensor == SensorType::kMa3 && ma3_) chosen = &*ma3_;
  if (cfg.sensor == SensorType::kMag && mag_) chosen = &*mag_;
  if (chosen != sensor_) {  // another sensor: start afresh
    have_pos_ = false;
    if (chosen != nullptr) chosen->restart();
  }
  sensor_ = chosen;
  if (first) coast_s_ = cfg.coast_s;
  // A new offset moves the reported position; shift the history with it so the
  // plausibility check does not take the change for a jump.
  if (have_pos_ && offset_change != 0.0f) {
    pos_deg_ += offset_change;
    for (auto& s : history_) s.deg += offset_change;
    if (request_.kind == RequestKind::kGoto) request_.kind = RequestKind::kNone;
  }
}

void Axis::begin(Millis now) {
  now_ = last_tick_ = now;
  out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  if (sensor_ == nullptr) latch_fault(AxisFault::kNoSensor);
  read_switches();
  update_position(now);
  publish();
}

void Axis::shutdown() {
  seq_.cancel();
  out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  request_ = {};
  if (state_ != AxisState::kFault) state_ = AxisState::kIdle;
  publish();
}

Error Axis::go_to(float target_deg) {
  if (state_ == AxisState::kFault) return Error::kFaulted;
  if (cfg_.continuous) target_deg = unwrap_near(target_deg, pos_deg_);
  if (!cfg_.continuous && (target_deg < cfg_.min_deg || target_deg > cfg_.max_deg))
    return Error::kOutOfRange;
  if (request_.kind != RequestKind::kGoto || request_.target_deg != target_deg) {
    starts_this_request_ = 0;
    move_started_ = now_;
    move_distance_deg_ = std::fabs(target_deg - pos_deg_);
  }
  request_ = {RequestKind::kGoto, target_deg, Direction::kNone, 0};
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
  publish();
}

void Axis::clear_fault() {
  if (state_ != AxisState::kFault) return;
  fault_ = AxisFault::kNone;
  state_ = AxisState::kIdle;
  stop_done_at_ = now_;
  jump_rejects_ = 0;
  bad_since_ = -1;
  if (sensor_ == nullptr) latch_fault(AxisFault::kNoSensor);
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
  fault_ = fault;
  state_ = AxisState::kFault;
  dir_ = Direction::kNone;
  reversing_ = false;
}

float Axis::initial_unwrap(float sensor_deg) const {
  // A single-turn sensor repeats every 360 deg. At start-up pick the turn
  // inside the travel; when the travel holds two candidates, the overlap
  // threshold inputs decide (T1: beyond 360, T2: below 0), else the one in
  // 0..360 wins.
  const float lo = cfg_.min_deg - 5.0f;
  const float hi = cfg_.max_deg + 5.0f;
  float lowest = 0.0f, highest = 0.0f, compass = 0.0f;
  bool any = false, in_compass = false;
  for (int turn = -2; turn <= 3; ++turn) {
    const float user = sensor_deg + cfg_.offset_deg + 360.0f * static_cast<float>(turn);
    if (user < lo || user > hi) continue;
    if (!any || user < lowest) lowest = user;
    if (!any || user > highest) highest = user;
    if (user >= 0.0f && user < 360.0f) {
      compass = user;
      in_compass = true;
    }
    any = true;
  }
  float user = sensor_deg + cfg_.offset_deg;
  if (any) user = t1_ ? highest : t2_ ? lowest : in_compass ? compass : lowest;
  return user - cfg_.offset_deg;
}

void Axis::update_position(Millis now) {
  if (sensor_ == nullptr) return;
  const PositionReading r = sensor_->read(now);
  raw_ = r.raw;
  // A weak or distorted field still gives raw samples, which is what the
  // magnetometer calibration needs; only a silent chip gives none.
  mag_answered_ = r.ok || r.fault != SensorFault::kNoSignal;
  if (!r.ok) {
    if (bad_since_ < 0) bad_since_ = now;
    if (now - bad_since_ >= kSensorGraceMs && state_ != AxisState::kFault) {
      latch_fault(r.fault == SensorFault::kOutOfRange    ? AxisFault::kSensorRange
                  : r.fault == SensorFault::kImplausible ? AxisFault::kSensorJump
                                                         : AxisFault::kSensorLost);
    }
    return;
  }
  bad_since_ = -1;
  float sensor_deg = r.deg;
  if (sensor_->single_turn() && !cfg_.continuous) {
    sensor_deg = have_pos_ ? unwrap_near(r.deg, sensor_deg_) : initial_unwrap(r.deg);
    // After a recalibration stay on the turn the axis was on, unless that
    // turn is now outside the travel.
    const float user = sensor_deg + cfg_.offset_deg;
    if (recalibrated_ && (user < cfg_.min_deg - 5.0f || user > cfg_.max_deg + 5.0f))
      sensor_deg = initial_unwrap(r.deg);
  } else if (sensor_->single_turn()) {
    sensor_deg = have_pos_ ? unwrap_near(r.deg, sensor_deg_) : r.deg;
  }
  const float pos = sensor_deg + cfg_.offset_deg;
  if (recalibrated_) {
    recalibrated_ = false;
    jump_rejects_ = 0;
    history_count_ = 0;  // the old samples are in the old frame
    if (request_.kind == RequestKind::kGoto) request_.kind = RequestKind::kNone;
  } else if (have_pos_ && std::fabs(pos - pos_deg_) > cfg_.jump_deg) {
    // Reject the sample; a real rotator cannot move this far in one tick.
    if (++jump_rejects_ >= kJumpRejectLimit && state_ != AxisState::kFault)
      latch_fault(AxisFault::kSensorJump);
    return;
  }
  jump_rejects_ = 0;
  sensor_deg_ = sensor_deg;
  pos_deg_ = pos;
  have_pos_ = true;
  history_[static_cast<std::size_t>(history_head_)] = {now, pos};
  history_head_ = (history_head_ + 1) % static_cast<int>(history_.size());
  if (history_count_ < static_cast<int>(history_.size())) ++history_count_;
}

float Axis::estimate_speed() const {
  // Slope over the last ~300 ms: long enough to average ADC noise, short
  // enough to follow a relay motor's spin-up.
  if (history_count_ < 2) return 0.0f;
  const int n = static_cast<int>(history_.size());
  const Sample& newest = history_[static_cast<std::size_t>((history_head_ - 1 + n) % n)];
  Sample oldest = newest;
  for (int k = 2; k <= history_count_; ++k) {
    const Sample& s = history_[static_cast<std::size_t>((history_head_ - k + n) % n)];
    oldest = s;
    if (newest.t - s.t >= 300) break;
  }
  const Millis dt = newest.t - oldest.t;
  if (dt <= 0) return 0.0f;
  return (newest.deg - oldest.deg) * 1000.0f / static_cast<float>(dt);
}

float Axis::stop_distance_deg() const {
  // Distance the antenna travels after the drive is cut: the learned coast
  // plus one tick of latency.
  return std::fabs(status_.speed_deg_s) * (coast_s_ + 0.01f);
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
      // A DC motor's speed grows with the duty above its dead band
      // (physics.md, H-bridge actuation).
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
      return std::fabs(request_.target_deg - pos_deg_);
    case RequestKind::kJog:
      // A jog may run to the end of the travel; an endless axis has no end,
      // and its jogs keep the configured timeout.
      if (cfg_.continuous) return 0.0f;
      return request_.dir == Direction::kCw ? cfg_.max_deg - pos_deg_ : pos_deg_ - cfg_.min_deg;
    case RequestKind::kNone:
      break;
  }
  return 0.0f;
}

void Axis::read_switches() {
  sw_cw_ = active(io_.limit_cw);
  sw_ccw_ = active(io_.limit_ccw);
  t1_ = active(io_.t1);
  t2_ = active(io_.t2);
}

bool Axis::blocked(Direction dir) const {
  if (dir == Direction::kCw) {
    if (sw_cw_) return true;
    return !cfg_.continuous && pos_deg_ + stop_distance_deg() >= cfg_.max_deg;
  }
  if (dir == Direction::kCcw) {
    if (sw_ccw_) return true;
    return !cfg_.continuous && pos_deg_ - stop_distance_deg() <= cfg_.min_deg;
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
  const float err = request_.target_deg - pos_deg_;
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

void Axis::begin_start(Direction dir, Millis now) {
  dir_ = dir;
  reversing_ = false;
  state_ = AxisState::kStarting;
  duty_ = cfg_.pwm_slow_duty;
  ++starts_this_request_;
  ++moves_;
  stall_ref_t_ = now;
  stall_ref_deg_ = pos_deg_;
  seq_.start(make_start_sequence(cfg_), dir, now);
  seq_.run(now, out_);
}

void Axis::begin_stop(bool hard, bool reversing, Millis now) {
  cut_deg_ = pos_deg_;
  cut_speed_deg_s_ = status_.speed_deg_s;
  reversing_ = reversing;
  state_ = reversing ? AxisState::kReversing : AxisState::kStopping;
  seq_.start(make_stop_sequence(cfg_, hard), dir_, now);
  seq_.run(now, out_);
  drive_off_at_ = now;
}

void Axis::drive_moving(Millis now) {
  // Near the target every drive slows down; elsewhere relay drives follow the
  // WRC convention (speed 1-50 slow, 51-100 fast) and PWM scales the duty.
  const bool near_target = request_.kind == RequestKind::kGoto &&
                           std::fabs(request_.target_deg - pos_deg_) <= cfg_.slow_zone_deg;
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
      const float target = commanded_duty(near_target);
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
}

void Axis::finish_stop(Millis now) {
  const float travelled = (pos_deg_ - cut_deg_) * sign_of(dir_);
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
  read_switches();
  update_position(now);
  status_.speed_deg_s = estimate_speed();

  if (state_ != AxisState::kFault) {
    const Direction want = desired_direction();
    switch (state_) {
      case AxisState::kIdle: {
        if (want == Direction::kNone) break;
        const Millis since_stop = now - stop_done_at_;
        const Millis wait = (want != last_dir_ && last_dir_ != Direction::kNone)
                                ? cfg_.reverse_dead_ms
                                : cfg_.min_dwell_ms;
        if (since_stop >= wait) begin_start(want, now);
        break;
      }
      case AxisState::kStarting:
      case AxisState::kMoving: {
        const bool hard =
            (dir_ == Direction::kCw && sw_cw_) || (dir_ == Direction::kCcw && sw_ccw_);
        if (want != dir_) {
          begin_stop(hard, want != Direction::kNone, now);
          break;
        }
        if (state_ == AxisState::kStarting) {
          if (!seq_.run(now, out_)) state_ = AxisState::kMoving;
          break;
        }
        drive_moving(now);
        if (std::fabs(pos_deg_ - stall_ref_deg_) >= cfg_.stall_deg) {
          stall_ref_deg_ = pos_deg_;
          stall_ref_t_ = now;
        } else if (now - stall_ref_t_ >= cfg_.stall_ms) {
          latch_fault(AxisFault::kStall);
        }
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

  // Interlock, whatever the state: never both directions at once.
  if (out_.on(OutputChannel::kRelayCw) && out_.on(OutputChannel::kRelayCcw)) out_.all_off();
  if (out_.on(OutputChannel::kPwmCw) && out_.on(OutputChannel::kPwmCcw)) out_.all_off();
  if (io_.drive) io_.drive->apply(out_);
  last_tick_ = now;
  publish();
}

float Axis::reported_position_deg() const {
  // At rest on a range end a noisy sensor reads a little beyond it (-0.14 at
  // the CCW stop, 450.16 at the CW one). Clients such as Hamlib refuse to
  // send back a position outside the limits they were given, so an excess
  // within the go-to tolerance is reported as the range end; a real
  // overtravel beyond that stays visible.
  if (pos_deg_ < cfg_.min_deg && pos_deg_ >= cfg_.min_deg - cfg_.tolerance_deg) return cfg_.min_deg;
  if (pos_deg_ > cfg_.max_deg && pos_deg_ <= cfg_.max_deg + cfg_.tolerance_deg) return cfg_.max_deg;
  return pos_deg_;
}

void Axis::publish() {
  status_.present = true;
  status_.position_valid = have_pos_;
  status_.position_deg = cfg_.continuous ? wrap_360(pos_deg_) : reported_position_deg();
  status_.raw = raw_;
  status_.raw_full_scale = 0.0f;
  status_.adc_ref_v = 0.0f;
  status_.mag_valid = false;
  if (sensor_ != nullptr) {  // the configured sensor is fitted
    switch (cfg_.sensor) {
      case SensorType::kPot:
        status_.raw_full_scale = static_cast<float>(io_.pot->full_scale_counts());
        status_.adc_ref_v = io_.pot->reference_v();
        break;
      case SensorType::kMa3:
        status_.raw_full_scale = static_cast<float>(ma3_timing(cfg_.ma3_bits).counts);
        break;
      case SensorType::kMag: {
        const MagSample& m = mag_->last_sample();
        status_.mag_valid = mag_answered_;
        status_.mag_x = m.x;
        status_.mag_y = m.y;
        status_.mag_z = m.z;
        break;
      }
    }
  }
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
  status_.switch_cw = sw_cw_;
  status_.switch_ccw = sw_ccw_;
  status_.limit_cw = sw_cw_ || (!cfg_.continuous && pos_deg_ >= cfg_.max_deg - cfg_.tolerance_deg);
  status_.limit_ccw =
      sw_ccw_ || (!cfg_.continuous && pos_deg_ <= cfg_.min_deg + cfg_.tolerance_deg);
  status_.t1 = t1_;
  status_.t2 = t2_;
  status_.coast_s = coast_s_;
  status_.moves = moves_;
  status_.outputs = out_;
}

}  // namespace rotord
