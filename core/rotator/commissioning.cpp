#include "rotator/commissioning.hpp"

#include <cmath>
#include <cstring>

#include "motion/angles.hpp"

namespace rotord {
namespace {

using settings::Id;

// Timings of the measuring runs (controller time).
constexpr Millis kNoiseMs = 2000;     // at rest, sampling the sensor
constexpr Millis kNudgeMs = 1500;     // each nudge, once the motor runs
constexpr Millis kSettleMs = 1500;    // a run's speed is fitted after this
constexpr Millis kRunMs = 5000;       // the reversal and same-direction runs
constexpr Millis kFastRunMs = 8000;   // the fast-level run, at most
constexpr int kRestSamples = 50;      // readings averaged at rest after a stop
constexpr float kWrongWayDeg = 2.0f;  // a reading this far the wrong way aborts
// Stall detection while commissioning: a stop is found within a second.
constexpr float kStallDeg = 0.5f;
constexpr int kStallMs = 1500;
constexpr float kSeekMinDeg = 5.0f;  // a seek that stalls sooner did not find an end

float sign_of(Direction d) {
  return d == Direction::kCw ? 1.0f : d == Direction::kCcw ? -1.0f : 0.0f;
}
Direction other_way(Direction d) {
  return d == Direction::kCw ? Direction::kCcw : Direction::kCw;
}
float clampf(float v, float lo, float hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

struct AxisKeys {
  Id min_deg, max_deg, tolerance, slow_zone, stall_ms, speed, slow_ratio, dead_band, coast;
  Id cal_lo_counts, cal_lo_deg, cal_hi_counts, cal_hi_deg, cal_mid_points;
  Id relay_cw, relay_ccw, pwm_cw, pwm_ccw, line_cw, line_ccw;
};
constexpr AxisKeys kAz{
    Id::kAzMinDeg,      Id::kAzMaxDeg,          Id::kAzToleranceDeg,   Id::kAzSlowZoneDeg,
    Id::kAzStallMs,     Id::kAzSpeedDegS,       Id::kAzSlowSpeedRatio, Id::kAzPwmDeadBand,
    Id::kAzCoastS,      Id::kAzPotCalLoCounts,  Id::kAzPotCalLoDeg,    Id::kAzPotCalHiCounts,
    Id::kAzPotCalHiDeg, Id::kAzPotCalMidPoints, Id::kPinAzCw,          Id::kPinAzCcw,
    Id::kPinAzPwmCw,    Id::kPinAzPwmCcw,       Id::kGpiodAzCw,        Id::kGpiodAzCcw};
constexpr AxisKeys kEl{
    Id::kElMinDeg,      Id::kElMaxDeg,          Id::kElToleranceDeg,   Id::kElSlowZoneDeg,
    Id::kElStallMs,     Id::kElSpeedDegS,       Id::kElSlowSpeedRatio, Id::kElPwmDeadBand,
    Id::kElCoastS,      Id::kElPotCalLoCounts,  Id::kElPotCalLoDeg,    Id::kElPotCalHiCounts,
    Id::kElPotCalHiDeg, Id::kElPotCalMidPoints, Id::kPinElUp,          Id::kPinElDown,
    Id::kPinElPwmUp,    Id::kPinElPwmDown,      Id::kGpiodElUp,        Id::kGpiodElDown};

}  // namespace

float Commissioning::Run::slope() const {
  const double den = n * stt - st * st;
  return den > 0.0 ? static_cast<float>((n * stx - st * sx) / den) : 0.0f;
}
float Commissioning::Run::intercept() const {
  return n > 0.0 ? static_cast<float>((sx - static_cast<double>(slope()) * st) / n) : 0.0f;
}

Error Commissioning::start(const Request& request, Axis& axis, const char** why) {
  const AxisStatus& s = axis.status();
  if (s.fault == AxisFault::kNoSensor || !s.position_valid) {
    *why = "no position sensor is fitted or it gives no reading";
    return Error::kNotSupported;
  }
  if (s.fault != AxisFault::kNone) {
    *why = "a fault is latched: clear it (RESET) first";
    return Error::kFaulted;
  }
  if (running()) {
    *why = "self-commissioning is already running";
    return Error::kBusy;
  }
  if (request.step == Step::kBearing) return propose_bearing(request, axis, why);
  if (!(request.cw_stop_deg > request.ccw_stop_deg)) {
    *why = "the CW stop must lie above the CCW stop";
    return Error::kOutOfRange;
  }
  const bool needs_ends = request.step == Step::kSpeeds;
  if (needs_ends && (!m_.ends_known || !m_.direction_known || req_.axis != request.axis)) {
    *why = "the speeds step needs the direction and ends steps first";
    return Error::kInvalidArgument;
  }
  const bool keep = request.step != Step::kAll && req_.axis == request.axis;
  if (!keep) {
    m_ = Measured{};
    noise_frame_ = 0.0f;
  }
  req_ = request;
  saved_ = axis.config();
  // The commissioning frame: the configured calibration's end points only,
  // no soft limits, stall detection tightened, no move timeout.
  AxisConfig c = saved_;
  pot_ = c.sensor == SensorType::kPot;
  if (pot_) {
    const auto& p = c.pot_cal.points;
    const auto& lo = p[0];
    const auto& hi = p[static_cast<std::size_t>(c.pot_cal.count - 1)];
    c.pot_cal = PotCalibration::two_point(lo.counts, lo.deg, hi.counts, hi.deg);
    cal_b_ = (hi.deg - lo.deg) / (hi.counts - lo.counts);
    cal_a_ = lo.deg - cal_b_ * lo.counts;
  }
  c.min_deg = -100000.0f;
  c.max_deg = 100000.0f;
  c.continuous = false;
  c.stall_deg = kStallDeg;
  // The brake's release and a reversal's backlash come before any motion.
  c.stall_ms = kStallMs + (c.has_brake ? c.brake_release_ms : 0);
  c.move_timeout_ms = 3600000;
  c.coast_learn = false;
  c.jump_deg = 180.0f;
  axis.configure(c);
  axis.stop();
  reason_ = "";
  state_ = State::kRunning;
  samples_n_ = 0;
  sample_every_ms_ = 250;
  proposals_n_ = 0;
  started_at_ = last_sample_at_ = last_tick_at_ = -1;
  coast_sum_ = 0.0f;
  coast_count_ = 0;
  noise_n_ = noise_mean_ = noise_m2_ = 0.0;
  const Phase first = request.step == Step::kEnds     ? Phase::kSeekCcw
                      : request.step == Step::kSpeeds ? Phase::kPrime
                                                      : Phase::kNoise;
  // Nudge away from a closed end switch first.
  nudge_dir_[0] = s.switch_cw ? Direction::kCcw : Direction::kCw;
  nudge_dir_[1] = other_way(nudge_dir_[0]);
  phase_ = first;
  phase_at_ = -1;
  run_.clear();
  *why = "";
  return Error::kOk;
}

// The known bearing moves nothing. An absolute sensor reads degrees whatever
// its zero, so one bearing the owner gives (a landmark, the Sun) fixes the
// zero: the reading moves by exactly a change of it (the axis unwraps it into
// its travel), so the proposal turns it by the shortest way from the reading
// to the bearing. A pot's calibration comes from the ends instead.
Error Commissioning::propose_bearing(const Request& request, const Axis& axis, const char** why) {
  const float bearing_deg = request.bearing_deg;
  const AxisConfig& c = axis.config();
  *why = "the bearing is a number from 0 to 360";
  if (!(bearing_deg >= 0.0f && bearing_deg <= 360.0f)) return Error::kOutOfRange;
  *why = "a pot has no zero: the ends step calibrates it";
  if (c.sensor == SensorType::kPot) return Error::kNotSupported;
  *why = "the antenna is moving";
  if (axis.status().state != AxisState::kIdle) return Error::kBusy;
  const float turn_deg = wrap_180(bearing_deg - axis.status().position_deg);
  req_ = request;
  m_ = Measured{};  // the ends of a sensor's old zero
  samples_n_ = 0;
  proposals_n_ = 0;
  // The MA3 reads its code less the zero; the magnetometer's heading is
  // magnetic plus declination (and so takes its mounting angle too).
  if (c.sensor == SensorType::kMa3)
    add(request.axis == AxisId::kEl ? Id::kElMa3ZeroDeg : Id::kAzMa3ZeroDeg,
        wrap_360(c.ma3_zero_deg - turn_deg));
  else
    add(Id::kMagDeclinationDeg, wrap_180(c.mag_cal.declination_deg + turn_deg));
  reason_ = "";
  state_ = State::kDone;
  phase_ = Phase::kFinished;
  *why = "";
  return Error::kOk;
}

float Commissioning::reading(const Axis& axis) const {
  return axis.status().position_deg;  // the commissioning frame
}

float Commissioning::deg_per_unit() const {
  if (!m_.ends_known || m_.cw_reading == m_.ccw_reading) return 1.0f;
  return (req_.cw_stop_deg - req_.ccw_stop_deg) / (m_.cw_reading - m_.ccw_reading);
}

float Commissioning::to_deg(float x) const {
  if (!m_.ends_known) return x;
  return req_.ccw_stop_deg + (x - m_.ccw_reading) * deg_per_unit();
}

float Commissioning::sensor_lag_s() const {
  if (!pot_) return 0.0f;
  // A median of three readings lags a ramp by one tick; the low-pass by its
  // time constant.
  const float tick_s = static_cast<float>(tick_ms_) / 1000.0f;
  return (saved_.pot_filter.median ? tick_s : 0.0f) +
         static_cast<float>(saved_.pot_filter.lowpass_ms) / 1000.0f;
}

void Commissioning::record(Millis now, const Axis& axis) {
  if (started_at_ < 0) started_at_ = now;
  if (last_sample_at_ >= 0 && now - last_sample_at_ < sample_every_ms_) return;
  last_sample_at_ = now;
  if (samples_n_ == kMaxSamples) {
    // Full: keep every other sample and halve the rate (fixed memory).
    for (std::size_t k = 0; k < kMaxSamples / 2; ++k) samples_[k] = samples_[2 * k];
    samples_n_ = kMaxSamples / 2;
    sample_every_ms_ *= 2;
  }
  samples_[samples_n_++] = {static_cast<std::int32_t>(now - started_at_), reading(axis),
                            axis.status().speed_deg_s};
}

void Commissioning::enter(Phase phase, Millis now) {
  phase_ = phase;
  phase_at_ = now;
  run_.clear();
}

void Commissioning::abort(Axis& axis, const char* reason) {
  if (state_ != State::kRunning) return;
  axis.stop();
  axis.configure(saved_);
  state_ = State::kAborted;
  reason_ = reason;
}

void Commissioning::tick(Millis now, Axis& axis) {
  if (state_ != State::kRunning) return;
  const AxisStatus& s = axis.status();
  if (last_tick_at_ >= 0 && now > last_tick_at_) tick_ms_ = now - last_tick_at_;
  last_tick_at_ = now;
  record(now, axis);
  if (phase_at_ < 0) enter(phase_, now);
  const bool seeking = phase_ == Phase::kSeekCcw || phase_ == Phase::kSeekCw;
  if (s.fault != AxisFault::kNone && !(seeking && s.fault == AxisFault::kStall)) {
    abort(axis, s.fault == AxisFault::kStall
                    ? "the position stopped changing while the motor ran (stall)"
                    : "an axis fault latched");
    return;
  }
  if (phase_ == Phase::kNoise) {
    const double x = reading(axis);
    noise_n_ += 1.0;
    const double d = x - noise_mean_;
    noise_mean_ += d / noise_n_;
    noise_m2_ += d * (x - noise_mean_);
    if (now - phase_at_ >= kNoiseMs) {
      noise_frame_ = static_cast<float>(std::sqrt(noise_m2_ / noise_n_));
      next_after(Phase::kNoise, now, axis);
    }
    return;
  }
  tick_run(now, axis);
}

void Commissioning::tick_run(Millis now, Axis& axis) {
  const AxisStatus& s = axis.status();
  float x = reading(axis);
  // Which jog this phase makes: logical direction and speed level.
  Direction phys = Direction::kCw;
  int pct = 1;
  Millis length_ms = kRunMs;
  switch (phase_) {
    case Phase::kNudge1:
    case Phase::kNudge2:
      phys = nudge_dir_[phase_ == Phase::kNudge1 ? 0 : 1];
      length_ms = kNudgeMs;
      break;
    case Phase::kSeekCcw:
      phys = Direction::kCcw;
      length_ms = 0;
      break;
    case Phase::kSeekCw:
      phys = Direction::kCw;
      length_ms = 0;
      break;
    case Phase::kApproachCw:
      pct = 100;
      length_ms = 0;
      break;
    case Phase::kPrime:
      length_ms = kNudgeMs;
      break;
    case Phase::kRunReverse:
    case Phase::kRunSame:
      phys = Direction::kCcw;
      break;
    case Phase::kRunFast:
      phys = Direction::kCcw;
      pct = 100;
      length_ms = kFastRunMs;
      break;
    default:
      return;
  }
  const bool nudge = phase_ == Phase::kNudge1 || phase_ == Phase::kNudge2;
  const bool seek = phase_ == Phase::kSeekCcw || phase_ == Phase::kSeekCw;
  const bool approach = phase_ == Phase::kApproachCw;
  if (!run_.commanded) {
    if (s.state != AxisState::kIdle) return;  // the last stop is still settling
    if (seek && (phys == Direction::kCw ? s.switch_cw : s.switch_ccw)) {
      // Already at this end's switch: its reading is the end's.
      (phys == Direction::kCw ? m_.cw_reading : m_.ccw_reading) = x;
      next_after(phase_, now, axis);
      return;
    }
    axis.set_speed_pct(pct);
    const Error e = axis.jog(phys, 0);
    if (e != Error::kOk) {
      abort(axis, e == Error::kLimit ? "the rotator is at a limit in the direction to move"
                                     : "the axis refused to move");
      return;
    }
    run_.commanded = true;
    run_.start_x = x;
    return;
  }
  if (!run_.stopping) {
    if (run_.on_at < 0) {
      if (s.state == AxisState::kMoving) run_.on_at = now;
      if (s.state == AxisState::kIdle && !s.jogging) {
        abort(axis, "the axis stopped before the motor ran");
        return;
      }
      return;
    }
    const float t_s = static_cast<float>(now - run_.on_at) / 1000.0f;
    // Movement the way a known direction does not expect aborts at once.
    const float expect = sign_of(phys) * (nudge ? 0.0f : 1.0f);
    if (expect != 0.0f && (x - run_.start_x) * expect < -kWrongWayDeg) {
      abort(axis, "the reading went the wrong way");
      return;
    }
    if (now - run_.on_at >= kSettleMs) {
      run_.n += 1;
      run_.st += t_s;
      run_.sx += x;
      run_.stt += static_cast<double>(t_s) * t_s;
      run_.stx += static_cast<double>(t_s) * x;
    }
    bool end = false;
    if (length_ms > 0 && now - run_.on_at >= length_ms) end = true;
    if (!seek && !nudge && m_.ends_known) {
      // Measuring runs stop a margin short of the end they head for (never
      // into a stop faster than creep, and no stall in a measurement).
      const float end_deg = phys == Direction::kCw ? req_.cw_stop_deg : req_.ccw_stop_deg;
      const float left_deg = std::fabs(to_deg(x) - end_deg);
      const float travel_deg = req_.cw_stop_deg - req_.ccw_stop_deg;
      const float margin_deg = pct > 1 ? 0.1f * travel_deg + 10.0f : 0.02f * travel_deg + 3.0f;
      if (left_deg < margin_deg) end = true;
    }
    if (approach && x >= approach_until_) end = true;
    if (seek) {
      const bool at_switch = phys == Direction::kCw ? s.switch_cw : s.switch_ccw;
      const bool stalled = s.fault == AxisFault::kStall;
      if (stalled && std::fabs(x - run_.start_x) < kSeekMinDeg) {
        abort(axis, "the position stopped changing while the motor ran (stall)");
        return;
      }
      if (at_switch || stalled) {
        (phys == Direction::kCw ? m_.cw_reading : m_.ccw_reading) = x;
        if (stalled) axis.clear_fault();
        end = true;
      }
    }
    if (end) {
      axis.stop();
      run_.stopping = true;
      run_.stop_at = now;
    }
    return;
  }
  if (!run_.cut_seen) {
    // The axis cut the drive this tick: where the fitted line puts the
    // rotator then (one reading would carry the sensor's noise).
    run_.cut_seen = true;
    run_.cut_at = now;
    const float t_s = static_cast<float>(now - run_.on_at) / 1000.0f;
    run_.cut_x = run_.n > 10 ? run_.intercept() + run_.slope() * t_s : x;
  }
  if (s.state != AxisState::kIdle || now - run_.stop_at < 200) return;
  if (run_.rest_n < kRestSamples) {
    // At rest: the mean of a few readings.
    run_.rest_sum += x;
    ++run_.rest_n;
    return;
  }
  const float rest_x = run_.rest_sum / static_cast<float>(run_.rest_n);
  // The coast after the cut, at the fitted speed, less what the sensor's
  // filter delays the reading at the cut by. A relay's release time counts
  // as coast: to the axis's stopping rule it is.
  const float v = std::fabs(run_.slope());
  if (!seek && !nudge && !approach && run_.n > 10 && v > 0.05f) {
    const float coast_s = std::fabs(rest_x - run_.cut_x) / v - sensor_lag_s();
    coast_sum_ += coast_s > 0.0f ? coast_s : 0.0f;
    ++coast_count_;
  }
  x = rest_x;
  if (nudge) nudge_dx_[phase_ == Phase::kNudge1 ? 0 : 1] = (x - run_.start_x) * sign_of(phys);
  next_after(phase_, now, axis);
}

void Commissioning::next_after(Phase done, Millis now, Axis& axis) {
  const Step step = req_.step;
  switch (done) {
    case Phase::kNoise:
      enter(Phase::kNudge1, now);
      return;
    case Phase::kNudge1:
      enter(Phase::kNudge2, now);
      return;
    case Phase::kNudge2: {
      constexpr float kMovedDeg = 0.3f;
      const bool moved = std::fabs(nudge_dx_[0]) > kMovedDeg && std::fabs(nudge_dx_[1]) > kMovedDeg;
      if (!moved) return abort(axis, "the position did not change while the motor ran");
      if (nudge_dx_[0] > 0.0f && nudge_dx_[1] > 0.0f) {
        m_.swapped = false;
      } else if (nudge_dx_[0] < 0.0f && nudge_dx_[1] < 0.0f) {
        m_.swapped = true;
      } else {
        return abort(axis, "both outputs turned the rotator the same way");
      }
      m_.direction_known = true;
      // Swapped outputs end the run with the swap proposed: the owner
      // accepts it (the pins change places) and runs the rest again.
      if (step == Step::kDirection || m_.swapped) return finish(axis);
      enter(Phase::kSeekCcw, now);
      return;
    }
    case Phase::kSeekCcw: {
      // An absolute sensor reads degrees whatever its zero offset: once the
      // CCW end's reading is known, so is the CW end's, and the axis may run
      // at full speed to the margin the fast measuring run keeps from an end
      // (the end is still met at creep). A pot's span is not known before
      // both ends are: it creeps the whole way. On the spid's 720 deg at
      // 1.3-2 deg/s creep this saves most of the run.
      const float travel_deg = req_.cw_stop_deg - req_.ccw_stop_deg;
      const float margin_deg = 0.1f * travel_deg + 10.0f;
      approach_until_ = m_.ccw_reading + travel_deg - margin_deg;
      const bool fast_level = saved_.drive != DriveType::kRelay;
      const bool worth_it = approach_until_ - reading(axis) > margin_deg;
      enter(!pot_ && fast_level && worth_it ? Phase::kApproachCw : Phase::kSeekCw, now);
      return;
    }
    case Phase::kApproachCw:
      enter(Phase::kSeekCw, now);
      return;
    case Phase::kPrime:
      enter(Phase::kRunReverse, now);
      return;
    case Phase::kSeekCw:
      if (m_.cw_reading == m_.ccw_reading) return abort(axis, "both ends gave the same reading");
      m_.ends_known = true;
      m_.creep_deg_s = std::fabs(run_.slope() * deg_per_unit());
      if (step == Step::kEnds) return finish(axis);
      enter(Phase::kRunReverse, now);
      return;
    case Phase::kRunReverse:
      tau_reverse_s_ = (run_.start_x - run_.intercept()) / run_.slope();
      m_.creep_deg_s = std::fabs(run_.slope() * deg_per_unit());
      enter(Phase::kRunSame, now);
      return;
    case Phase::kRunSame: {
      const float tau_same_s = (run_.start_x - run_.intercept()) / run_.slope();
      const float v = std::fabs(run_.slope() * deg_per_unit());
      m_.creep_deg_s = 0.5f * (m_.creep_deg_s + v);
      m_.backlash_deg = clampf(m_.creep_deg_s * (tau_reverse_s_ - tau_same_s), 0.0f, 90.0f);
      if (saved_.drive == DriveType::kRelay) {
        m_.fast_deg_s = m_.creep_deg_s;
        m_.coast_s = coast_count_ > 0 ? coast_sum_ / static_cast<float>(coast_count_) : 0.0f;
        m_.speeds_known = true;
        return finish(axis);
      }
      enter(Phase::kRunFast, now);
      return;
    }
    case Phase::kRunFast: {
      m_.fast_deg_s = std::fabs(run_.slope() * deg_per_unit());
      m_.coast_s = coast_count_ > 0 ? coast_sum_ / static_cast<float>(coast_count_) : 0.0f;
      if (saved_.drive == DriveType::kHBridge && m_.fast_deg_s > m_.creep_deg_s) {
        // Speed grows linearly with the duty above the dead band.
        const float d1 = saved_.pwm_slow_duty, d2 = saved_.pwm_fast_duty;
        const float v1 = m_.creep_deg_s, v2 = m_.fast_deg_s;
        m_.dead_band = clampf((d1 * v2 - d2 * v1) / (v2 - v1), 0.0f, 0.95f);
      }
      m_.speeds_known = true;
      return finish(axis);
    }
    default:
      return;
  }
}

void Commissioning::finish(Axis& axis) {
  m_.noise_deg = noise_frame_ * std::fabs(deg_per_unit());
  axis.stop();
  axis.configure(saved_);
  propose(saved_);
  state_ = State::kDone;
  phase_ = Phase::kFinished;
}

void Commissioning::add(Id id, double value) {
  // Three decimals: a measurement carries no more (and a float's tail
  // would read as noise on the page).
  if (proposals_n_ < kMaxProposals)
    proposals_[proposals_n_++] = {id, std::round(value * 1000.0) / 1000.0};
}

void Commissioning::propose(const AxisConfig& base) {
  const AxisKeys& k = req_.axis == AxisId::kEl ? kEl : kAz;
  proposals_n_ = 0;
  const float noise_deg = m_.noise_deg;
  if (m_.ends_known) {
    if (pot_) {
      add(k.cal_lo_counts, (m_.ccw_reading - cal_a_) / cal_b_);
      add(k.cal_lo_deg, req_.ccw_stop_deg);
      add(k.cal_hi_counts, (m_.cw_reading - cal_a_) / cal_b_);
      add(k.cal_hi_deg, req_.cw_stop_deg);
      add(k.cal_mid_points, 0);
    }
    const float coast_deg = m_.speeds_known ? m_.fast_deg_s * m_.coast_s : 0.0f;
    const float margin = clampf(coast_deg + 3.0f * noise_deg, 1.0f, 30.0f);
    add(k.min_deg, req_.ccw_stop_deg + margin);
    add(k.max_deg, req_.cw_stop_deg - margin);
  }
  if (m_.speeds_known) {
    add(k.tolerance, clampf(4.0f * noise_deg + 0.5f * m_.backlash_deg, 0.3f, 10.0f));
    add(k.slow_zone, clampf(m_.fast_deg_s * (m_.coast_s + 1.0f), 1.0f, 90.0f));
    const float creep = m_.creep_deg_s > 0.05f ? m_.creep_deg_s : 0.05f;
    const float brake_ms = base.has_brake ? static_cast<float>(base.brake_release_ms) : 0.0f;
    add(k.stall_ms,
        std::round(clampf(3000.0f * base.stall_deg / creep + brake_ms, 1000.0f, 60000.0f)));
    add(k.coast, clampf(m_.coast_s, 0.0f, 5.0f));
    if (base.drive == DriveType::kHBridge && m_.dead_band >= 0.0f) {
      const float d2 = base.pwm_fast_duty;
      const float rated = m_.fast_deg_s * (1.0f - m_.dead_band) / (d2 - m_.dead_band);
      add(k.speed, clampf(rated, 0.1f, 60.0f));
      add(k.dead_band, m_.dead_band);
    } else {
      add(k.speed, clampf(m_.fast_deg_s, 0.1f, 60.0f));
      if (base.drive != DriveType::kRelay && m_.fast_deg_s > 0.0f)
        add(k.slow_ratio, clampf(m_.creep_deg_s / m_.fast_deg_s, 0.05f, 1.0f));
    }
  }
}

settings::Rejection Commissioning::apply_proposal(settings::Settings& s) const {
  const AxisKeys& k = req_.axis == AxisId::kEl ? kEl : kAz;
  settings::Settings scratch = s;
  if (proposes_swap()) {
    // The outputs change places: the CW and CCW pins (Pico), PWM pins and
    // GPIO lines (Pi), so the wiring stays as it is.
    const Id pairs[3][2] = {
        {k.relay_cw, k.relay_ccw}, {k.pwm_cw, k.pwm_ccw}, {k.line_cw, k.line_ccw}};
    for (const auto& pair : pairs) {
      const double a = s.get(pair[0]);
      const double b = s.get(pair[1]);
      scratch.set(pair[0], b);
      scratch.set(pair[1], a);
    }
  }
  for (std::size_t n = 0; n < proposals_n_; ++n) {
    const Proposal& p = proposals_[n];
    const settings::Rejection r = scratch.set(p.id, p.value);
    if (r.error != Error::kOk) return r;
  }
  const settings::Rejection rule = scratch.check_consistency();
  if (rule.error != Error::kOk) return rule;
  for (std::size_t id = 0; id < settings::kCount; ++id) s.copy_value(static_cast<Id>(id), scratch);
  return {};
}

const char* Commissioning::phase_name() const {
  switch (phase_) {
    case Phase::kNoise:
      return "noise";
    case Phase::kNudge1:
    case Phase::kNudge2:
      return "direction";
    case Phase::kSeekCcw:
      return "ccw_end";
    case Phase::kApproachCw:
    case Phase::kSeekCw:
      return "cw_end";
    case Phase::kPrime:
    case Phase::kRunReverse:
      return "backlash";
    case Phase::kRunSame:
      return "coast";
    case Phase::kRunFast:
      return "fast_speed";
    case Phase::kFinished:
      break;
  }
  return "finished";
}

const char* commissioning_state_name(Commissioning::State state) {
  switch (state) {
    case Commissioning::State::kIdle:
      return "idle";
    case Commissioning::State::kRunning:
      return "running";
    case Commissioning::State::kDone:
      return "done";
    case Commissioning::State::kAborted:
      return "aborted";
  }
  return "idle";
}

bool parse_commissioning_step(const char* name, std::size_t len, Commissioning::Step& out) {
  struct Entry {
    const char* name;
    Commissioning::Step step;
  };
  constexpr Entry kSteps[] = {{"all", Commissioning::Step::kAll},
                              {"direction", Commissioning::Step::kDirection},
                              {"ends", Commissioning::Step::kEnds},
                              {"speeds", Commissioning::Step::kSpeeds},
                              {"bearing", Commissioning::Step::kBearing}};
  for (const Entry& e : kSteps) {
    if (std::strlen(e.name) == len && std::memcmp(e.name, name, len) == 0) {
      out = e.step;
      return true;
    }
  }
  return false;
}

}  // namespace rotord
