#include "axis/position_tracker.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord {
namespace {

/// True when the active sensor's calibration differs: the same shaft position
/// then reads as another angle, in one step.
bool sensor_frame_changed(const AxisConfig& a, const AxisConfig& b) {
  if (a.sensor != b.sensor) return false;  // a new sensor starts afresh anyway
  return sensor_info(b.sensor).frame_changed(a, b);
}

bool active(hal::DigitalIn* in) {
  return in != nullptr && in->active();
}

}  // namespace

PositionTracker::PositionTracker(const AxisIo& io, const AxisConfig& cfg) : io_(io), cfg_(cfg) {
  for (const SensorInfo& type : sensor_types())
    fitted_[static_cast<std::size_t>(type.type)] = type.fit(sensors_, io_);
}

bool PositionTracker::configure(const AxisConfig& next) {
  const float offset_change = next.offset_deg - cfg_.offset_deg;
  // A recalibration (web page, GS-232 O/F) moves the reading in one step. The
  // next reading is taken as it comes, not rejected as an implausible jump:
  // that fault would latch, and no reset could clear it.
  if (sensor_ != nullptr && have_pos_ && sensor_frame_changed(cfg_, next)) recalibrated_ = true;
  for (const SensorInfo& type : sensor_types()) type.configure(sensors_, next);
  const SensorInfo& type = sensor_info(next.sensor);
  PositionSensor* chosen = fitted_[static_cast<std::size_t>(next.sensor)];
  if (chosen != sensor_) {  // another sensor: start afresh
    have_pos_ = false;
    if (chosen != nullptr) chosen->restart();
  }
  sensor_ = chosen;
  resolution_deg_ = type.resolution_deg(next);
  // A new offset moves the reported position; shift the history with it so the
  // plausibility check does not take the change for a jump.
  if (!have_pos_ || offset_change == 0.0f) return false;
  pos_deg_ += offset_change;
  for (auto& s : history_) s.deg += offset_change;
  return true;
}

void PositionTracker::clear_errors() {
  jump_rejects_ = 0;
  bad_since_ = -1;
  rejected_bits_ = 0;
  resync_ = true;
}

void PositionTracker::read_switches() {
  sw_cw_ = active(io_.limit_cw);
  sw_ccw_ = active(io_.limit_ccw);
  t1_ = active(io_.t1);
  t2_ = active(io_.t2);
}

float PositionTracker::initial_unwrap(float sensor_deg) const {
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

PositionTracker::Update PositionTracker::update(Millis now) {
  Update u;
  if (sensor_ == nullptr) return u;
  note_loop_gap(now);
  const PositionReading r = sensor_->read(now);
  const float speed_deg_s = estimate_speed();  // of the readings taken so far
  note_raw(r.raw, now, speed_deg_s);
  raw_ = r.raw;
  // Whether the sensor answered at all: an implausible sample still counts
  // (the magnetometer's calibration needs those); only silence does not.
  answered_ = r.ok || r.fault != SensorFault::kNoSignal;
  if (!r.ok) {
    // A reading the sensor itself found implausible (a glitching PWM
    // frame) counts towards a burst like one the gate turned away.
    if (r.fault == SensorFault::kImplausible && have_pos_) {
      const AxisFault f = reject(now, speed_deg_s);
      if (f != AxisFault::kNone) u.fault = f;
    }
    if (bad_since_ < 0) bad_since_ = now;
    if (now - bad_since_ >= kSensorGraceMs && u.fault == AxisFault::kNone) {
      u.fault = r.fault == SensorFault::kOutOfRange    ? AxisFault::kSensorRange
                : r.fault == SensorFault::kImplausible ? AxisFault::kSensorJump
                                                       : AxisFault::kSensorLost;
    }
    return u;
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
    u.frame_changed = true;
  } else if (resync_ || !have_pos_) {
    // The first reading, or the first after a reset: no past to judge by.
    // The gate starts wide (1.25 x the tolerance) and narrows to the
    // sensor's noise as it learns it (a time constant of 64 readings).
    if (!have_pos_) noise_abs_deg_ = 0.5f * kGateFloorOfTolerance * cfg_.tolerance_deg;
    resync_ = false;
  } else if (std::fabs(pos - pos_deg_) > cfg_.jump_deg || !plausible(pos, now, speed_deg_s)) {
    // Reject the sample: a real rotator cannot move this far in one tick
    // (jump_deg), nor this far off its measured motion (the gate).
    u.fault = reject(now, speed_deg_s);
    return u;
  }
  rejected_bits_ = static_cast<std::uint16_t>(rejected_bits_ << 1);
  jump_rejects_ = 0;
  sensor_deg_ = sensor_deg;
  pos_deg_ = pos;
  pos_t_ = now;
  have_pos_ = true;
  history_[static_cast<std::size_t>(history_head_)] = {now, pos};
  history_head_ = (history_head_ + 1) % static_cast<int>(history_.size());
  if (history_count_ < static_cast<int>(history_.size())) ++history_count_;
  return u;
}

AxisFault PositionTracker::reject(Millis now, float speed_deg_s) {
  ++gated_;
  rejected_bits_ = static_cast<std::uint16_t>((rejected_bits_ << 1) | 1u);
  if (moving_) {
    const float carried_deg = speed_deg_s * static_cast<float>(now - pos_t_) * 0.001f;
    pos_deg_ += carried_deg;
    sensor_deg_ += carried_deg;
    pos_t_ = now;
  }
  return ++jump_rejects_ >= kJumpRejectLimit ? AxisFault::kSensorJump : AxisFault::kNone;
}

void PositionTracker::note_loop_gap(Millis now) {
  const Millis gap_ms = read_before_ ? now - read_t_ : 0;
  read_before_ = true;
  read_t_ = now;
  if (gap_ms > kGateMaxGapMs) {
    stall_ms_ = gap_ms;
    stall_readings_left_ = kStallReadings;
  } else if (stall_readings_left_ > 0) {
    --stall_readings_left_;
  }
}

// Runs on the Pico every tick: a dozen float operations (soft float on the
// M0+), no division, no heap.
bool PositionTracker::plausible(float pos, Millis now, float speed_deg_s) {
  // Where the measured motion puts the antenna now, and how far a reading
  // may sit from that: the sensor's own noise (learnt; never below 1.5 x
  // its resolution or half the tolerance), plus what a change of speed
  // could add since the last reading (up to the rated speed again, so a
  // start from rest is followed).
  Millis gap_ms = now - pos_t_;
  if (gap_ms > kGateMaxGapMs) gap_ms = kGateMaxGapMs;
  // The cap keeps a run of rejected readings (a burst) from opening the
  // gate for itself. A stall of the loop while driven is no such run: the
  // motor may have turned the antenna at up to the rated speed all through
  // it. Capped, a stall just after a start from rest (no speed measured
  // yet) read as a jump that no later reading could take back, as the
  // prediction stayed at rest: SENSOR_JUMP on a good sensor (the loop of
  // an emulated Pi stalls for half a second and more).
  if (moving_ && stall_readings_left_ > 0 && gap_ms < stall_ms_) gap_ms = stall_ms_;
  const float dt_s = static_cast<float>(now - pos_t_) * 0.001f;
  const float predicted_deg = moving_ ? pos_deg_ + speed_deg_s * dt_s : pos_deg_;
  const float innovation = pos - predicted_deg;
  const float abs_innovation = std::fabs(innovation);
  float noise_deg = kGateNoiseFactor * noise_abs_deg_;
  float floor_deg = kGateFloorOfTolerance * cfg_.tolerance_deg;
  if (floor_deg < 1.5f * resolution_deg_) floor_deg = 1.5f * resolution_deg_;
  if (noise_deg < floor_deg) noise_deg = floor_deg;
  const float gate_deg =
      noise_deg + (std::fabs(speed_deg_s) + cfg_.speed_deg_s) * static_cast<float>(gap_ms) * 0.001f;
  // In a burst nothing is taken, however close: a reading that lands near
  // the prediction by chance is still noise.
  if (__builtin_popcount(rejected_bits_) >= kBurstRejects) return false;
  if (abs_innovation <= gate_deg) {
    // Learn the noise slowly (1/64 per reading) from readings taken only,
    // so a burst cannot open the gate for itself.
    noise_abs_deg_ += (abs_innovation - noise_abs_deg_) * (1.0f / 64.0f);
    return true;
  }
  return false;
}

void PositionTracker::note_raw(float raw, Millis now, float speed_deg_s) {
  if (raw == raw_) return;
  raw_changed_at_ = now;
  speed_at_change_deg_s_ = speed_deg_s;
}

float PositionTracker::estimate_speed() const {
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
  // Over a shorter span (the first readings after a start-up or a
  // recalibration) a pot's noise alone is tens of deg/s: two readings 10 ms
  // apart that differ by 0.4 deg read as 40 deg/s. Such a "speed" made the
  // stop rule cut a 2 deg move at its start (bench, commissioning rows);
  // until the readings span enough time, no speed is claimed.
  constexpr Millis kMinSpanMs = 100;
  if (dt < kMinSpanMs) return 0.0f;
  return (newest.deg - oldest.deg) * 1000.0f / static_cast<float>(dt);
}

float PositionTracker::reported_position_deg() const {
  // At rest on a range end a noisy sensor reads a little beyond it (-0.14 at
  // the CCW stop, 450.16 at the CW one). Clients such as Hamlib refuse to
  // send back a position outside the limits they were given, so an excess
  // within the go-to tolerance is reported as the range end; a real
  // overtravel beyond that stays visible.
  if (pos_deg_ < cfg_.min_deg && pos_deg_ >= cfg_.min_deg - cfg_.tolerance_deg) return cfg_.min_deg;
  if (pos_deg_ > cfg_.max_deg && pos_deg_ <= cfg_.max_deg + cfg_.tolerance_deg) return cfg_.max_deg;
  return pos_deg_;
}

void PositionTracker::publish(AxisStatus& status) const {
  status.position_valid = have_pos_;
  status.position_deg = cfg_.continuous ? wrap_360(pos_deg_) : reported_position_deg();
  status.raw = raw_;
  status.raw_full_scale = 0.0f;
  status.adc_ref_v = 0.0f;
  status.mag_valid = false;
  if (sensor_ != nullptr)  // the configured sensor is fitted
    sensor_info(cfg_.sensor).publish(sensors_, io_, cfg_, answered_, status);
  status.readings_rejected = gated_;
  status.switch_cw = sw_cw_;
  status.switch_ccw = sw_ccw_;
  status.limit_cw = sw_cw_ || (!cfg_.continuous && pos_deg_ >= cfg_.max_deg - cfg_.tolerance_deg);
  status.limit_ccw = sw_ccw_ || (!cfg_.continuous && pos_deg_ <= cfg_.min_deg + cfg_.tolerance_deg);
  status.t1 = t1_;
  status.t2 = t2_;
}

}  // namespace rotord
