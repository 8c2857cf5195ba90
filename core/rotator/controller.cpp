#include "rotator/controller.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord {

using settings::Id;

const char* mode_name(Mode mode) {
  switch (mode) {
    case Mode::kIdle:
      return "idle";
    case Mode::kGoto:
      return "goto";
    case Mode::kManual:
      return "manual";
    case Mode::kPark:
      return "park";
    case Mode::kTrack:
      return "track";
    case Mode::kStow:
      return "stow";
  }
  return "?";
}

Controller::Controller(settings::Settings& settings, const AxisIo& az_io, const AxisIo& el_io)
    : settings_(settings),
      az_(AxisId::kAz, az_io),
      el_(AxisId::kEl, el_io),
      has_el_(settings.b(Id::kElEnabled)) {
  apply_settings();
  speed_pct_ = settings_.i(Id::kSpeedPct);
  az_.set_speed_pct(speed_pct_);
  el_.set_speed_pct(speed_pct_);
}

void Controller::apply_settings() {
  az_.configure(axis_config_from(settings_, AxisId::kAz));
  if (has_el_) el_.configure(axis_config_from(settings_, AxisId::kEl));
  wind_.configure(wind_config());
  applied_revision_ = settings_.revision();
}

void Controller::begin(Millis now) {
  now_ = now;
  last_activity_ms_ = now;
  az_.begin(now);
  if (has_el_) el_.begin(now);
  read_estop();
  count_faults();
}

void Controller::count_faults() {
  const AxisFault now_faults[kMaxAxes] = {az_.status().fault,
                                          has_el_ ? el_.status().fault : AxisFault::kNone};
  for (std::size_t n = 0; n < kMaxAxes; ++n) {
    const AxisFault f = now_faults[n];
    if (f != counted_fault_[n] && f != AxisFault::kNone)
      ++faults_latched_[n][static_cast<std::size_t>(f)];
    counted_fault_[n] = f;
  }
}

void Controller::read_estop() {
  if (estop_ == nullptr) return;
  // Not debounced: a stop acts on the first reading, and a normally-closed
  // contact makes a broken wire a stop too.
  const bool closed = estop_->active();
  estop_active_ = settings_.b(Id::kEstopNormallyClosed) ? !closed : closed;
  if (!estop_active_) return;
  az_.emergency_stop();
  if (has_el_) el_.emergency_stop();
  mode_ = Mode::kIdle;
}

void Controller::tick(Millis now) {
  now_ = now;
  if (settings_.revision() != applied_revision_) {
    // The commissioning frame is the settings' own: a change ends the run.
    if (commissioning_.running()) commissioning_.abort(commissioned_axis(), "the settings changed");
    apply_settings();
  }
  read_estop();
  tick_wind(now);
  if (recognition_.active && !settings_.b(Id::kTrackRecognise))
    end_recognition(RecognitionEnd::kOff);
  // A track or self-commissioning owns the axes: no re-hold after a slip.
  const bool rehold_allowed = !tracker_.armed() && !commissioning_.running();
  az_.allow_rehold(rehold_allowed);
  el_.allow_rehold(rehold_allowed);
  az_.tick(now);
  if (has_el_) el_.tick(now);
  if (commissioning_.running()) commissioning_.tick(now, commissioned_axis());
  tick_tracker(now);
  const RotatorStatus s = status();
  if (mode_ != Mode::kIdle && mode_ != Mode::kTrack && !s.moving() && !s.az.has_target &&
      !s.az.jogging && !(has_el_ && (s.el.has_target || s.el.jogging)))
    mode_ = Mode::kIdle;
  // An armed track counts as activity: no auto-park while waiting for AOS.
  if (mode_ != Mode::kIdle || s.moving() || tracker_.armed()) last_activity_ms_ = now;
  park_when_idle_long_enough(now);
  count_faults();
  count_wear(now);
}

void Controller::count_wear(Millis now) {
  // Allocation-free: fixed members only (this runs in the control tick).
  const AxisStatus& az = az_.status();
  const AxisStatus& el = el_.status();
  odometer_.observe(az, has_el_ ? el : AxisStatus{}, now);
  const int per_hour = settings_.i(Id::kCareMaxStartsH);
  Axis* axes[kMaxAxes] = {&az_, has_el_ ? &el_ : nullptr};
  for (std::size_t n = 0; n < kMaxAxes; ++n) {
    if (axes[n] == nullptr) continue;
    const AxisStatus& s = axes[n]->status();
    ceilings_[n].observe(s.moves, now, per_hour);
    // Decided here for the next tick's start: the axis holds a go-to at
    // rest while another start would pass the ceiling.
    axes[n]->hold_starts(!ceilings_[n].allows_start(per_hour));
    if (s.start_held && !was_held_[n]) ++starts_held_[n];
    was_held_[n] = s.start_held;
  }
}

void Controller::note_command() {
  // Any other command ends self-commissioning, as it ends a track.
  if (commissioning_.running())
    commissioning_.abort(commissioned_axis(), "another command took over");
  last_activity_ms_ = now_;
  auto_parked_ = false;
  end_track();
}

void Controller::end_track() {
  // A recognised pass ends with the track that follows it.
  if (recognition_.active) return end_recognition(RecognitionEnd::kCommand);
  if (!tracker_.armed()) return;
  tracker_.cancel();
  // The tracker paced the axes; the user's speed again.
  az_.set_speed_pct(speed_pct_);
  el_.set_speed_pct(speed_pct_);
  if (mode_ == Mode::kTrack) mode_ = Mode::kIdle;
}

std::optional<std::int64_t> Controller::utc_ms() const {
  if (utc_clock_ == nullptr) return std::nullopt;
  return utc_clock_->unix_ms();
}

tracking::Observer Controller::observer() const {
  tracking::Geodetic where;
  where.lat_deg = settings_.get(Id::kStationLatDeg);
  where.lon_deg = settings_.get(Id::kStationLonDeg);
  where.alt_m = settings_.get(Id::kStationAltM);
  return tracking::Observer(where);
}

bool Controller::station_set() const {
  return settings_.get(Id::kStationLatDeg) != 0.0 || settings_.get(Id::kStationLonDeg) != 0.0;
}

TrackError Controller::track(const TrackRequest& request) {
  if (wind_.refusing()) return TrackError::kStowed;
  note_command();  // ends a track already armed
  stream_.interrupt();
  // A fixed az/el needs no station; a satellite, the Sun and the Moon do.
  if (request.kind != tracking::TargetKind::kNone && !station_set()) return TrackError::kNoStation;
  const std::optional<std::int64_t> utc = utc_ms();
  if (!utc) return TrackError::kNoClock;
  if (!utc_clock_->synchronized() && !settings_.b(Id::kTimeTrustClock))
    return TrackError::kClockUnsynced;
  if (estop_active_) return TrackError::kFaulted;
  // What the rotator was doing gives way; the plan starts from where it stands.
  az_.stop();
  el_.stop();
  mode_ = Mode::kIdle;
  const TrackError e =
      tracker_.start(request, *utc, observer(), settings_, az_, has_el_ ? &el_ : nullptr);
  if (e == TrackError::kOk) mode_ = Mode::kTrack;
  return e;
}

void Controller::tick_tracker(Millis now) {
  if (!tracker_.armed()) return;
  const std::optional<std::int64_t> utc = utc_ms();
  if (!utc) return;  // the clock went away (cannot happen on the ports); wait
  const Tracker::Action action = tracker_.tick(now, *utc, az_, has_el_ ? &el_ : nullptr);
  if (tracker_.armed()) return;
  az_.set_speed_pct(speed_pct_);
  el_.set_speed_pct(speed_pct_);
  mode_ = Mode::kIdle;
  // A recognised pass ends at LOS as the client's own: it decides what next.
  if (recognition_.active)
    return end_recognition(action == Tracker::Action::kFailed ? RecognitionEnd::kFailed
                                                              : RecognitionEnd::kLos);
  switch (action) {
    case Tracker::Action::kPark:
      park();
      break;
    case Tracker::Action::kReturn: {
      std::optional<float> el;
      if (has_el_) el = tracker_.return_el_deg();
      if (go_to(tracker_.return_az_deg(), el, AzTarget::kUnwrapped) == Error::kOk)
        mode_ = Mode::kGoto;
      break;
    }
    case Tracker::Action::kNone:
    case Tracker::Action::kFailed:
      break;
  }
}

void Controller::park_when_idle_long_enough(Millis now) {
  const int after_min = settings_.i(Id::kParkAfterIdleMin);
  if (after_min <= 0 || auto_parked_) return;
  if (now - last_activity_ms_ < static_cast<Millis>(after_min) * 60000) return;
  // Once per idle spell: a refused park (latched fault) is not retried every
  // tick, and a parked rotator is not nudged again every N minutes.
  park();
  auto_parked_ = true;
}

void Controller::end_jog(AxisId axis) {
  Axis& a = axis == AxisId::kAz ? az_ : el_;
  if (a.status().jogging) a.stop();
}

void Controller::shutdown() {
  az_.shutdown();
  if (has_el_) el_.shutdown();
  mode_ = Mode::kIdle;
}

std::optional<float> Controller::resolve_az(float az_deg, AzTarget mode) const {
  const AxisConfig& c = az_.config();
  if (c.continuous) {
    if (az_deg < 0.0f || az_deg > 360.0f) return std::nullopt;
    return wrap_360(az_deg);
  }
  if (mode == AzTarget::kCompass && az_deg >= 0.0f && az_deg <= 360.0f)
    return choose_unwrapped_az(az_deg, az_.status().position_deg, c.min_deg, c.max_deg, false);
  if (az_deg < c.min_deg || az_deg > c.max_deg) return std::nullopt;
  return az_deg;
}

Error Controller::go_to(std::optional<float> az_deg, std::optional<float> el_deg, AzTarget az_mode,
                        CommandSource source) {
  last_goto_recognised_ = false;
  // Refused before anything changes: a recognised pass ended by the stow
  // is not re-begun, and a client's stream is not judged.
  if (wind_.refusing()) return Error::kStowed;
  bool literal = false;
  if (recognition_.active) {
    if (source == recognition_.source && az_deg && el_deg && on_recognised(*az_deg, *el_deg)) {
      // The client confirms the pass rotord follows: no command ends it.
      last_activity_ms_ = now_;
      auto_parked_ = false;
      ++recognition_.gotos;
      last_goto_recognised_ = true;
      const TrackPhase phase = tracker_.status().phase;
      if (phase != TrackPhase::kFinding && phase != TrackPhase::kPlanning &&
          phase != TrackPhase::kWaiting)
        return Error::kOk;
      // Until the follower has planned the pass, the go-to itself points.
      GotoStream::Step step;
      const Error e = goto_axes(az_deg, el_deg, az_mode, source, step);
      mode_ = Mode::kTrack;
      return e;
    }
    end_recognition(source == recognition_.source ? RecognitionEnd::kDeparted
                                                  : RecognitionEnd::kOtherSource);
    literal = true;
  }
  note_command();
  // The go-to that ended a recognition means what it says: a new stream.
  if (literal) stream_.interrupt();
  GotoStream::Step step;
  const Error e = goto_axes(az_deg, el_deg, az_mode, source, step);
  if (e == Error::kOk && az_deg && el_deg && !literal)
    consider_recognition(*az_deg, *el_deg, step, source);
  return e;
}

Error Controller::goto_axes(std::optional<float> az_deg, std::optional<float> el_deg,
                            AzTarget az_mode, CommandSource source, GotoStream::Step& step) {
  if (el_deg && !has_el_) return Error::kNotSupported;
  std::optional<float> az_target;
  float shift_deg = 0.0f;
  if (az_deg) {
    az_target = resolve_az(*az_deg, az_mode);
    if (!az_target) return Error::kOutOfRange;
    const AxisConfig& c = az_.config();
    step = stream_.judge(*az_deg, source, now_, c.continuous ? 360.0f : c.max_deg - c.min_deg);
    // Only a compass azimuth is resolved: a client that sends 420 means 420.
    if (!c.continuous && step.continues && settings_.b(Id::kTrackContinuity) && *az_deg >= 0.0f &&
        *az_deg <= 360.0f) {
      const float continued = unwrap_near(*az_deg, stream_.last_target_deg());
      // Never outside the travel: where the stream would leave it, the
      // literal turn (the unwind) is the only way on.
      if (continued >= c.min_deg && continued <= c.max_deg &&
          std::fabs(continued - *az_target) > 1.0f) {
        shift_deg = continued - *az_target;
        az_target = continued;
      }
    }
  }
  if (el_deg) {
    const AxisConfig& c = el_.config();
    if (*el_deg < c.min_deg || *el_deg > c.max_deg) return Error::kOutOfRange;
  }
  if (az_.status().fault != AxisFault::kNone || (has_el_ && el_.status().fault != AxisFault::kNone))
    return Error::kFaulted;
  // The lead rule: a tracker's stream moves each axis a lead ahead, or
  // holds it while the target is within the band (rotator/stream_lead.hpp).
  StreamLead::Plan az_plan, el_plan;
  if (az_target) az_plan.aim_deg = *az_target;
  if (el_deg) el_plan.aim_deg = *el_deg;
  if (az_target && step.continues && settings_.b(Id::kTrackStreamLead)) {
    lead_.az.note(*az_target);
    if (el_deg) lead_.el.note(*el_deg);
    // What the client saw: its error when it decided to send (a Gpredict
    // sends only beyond its threshold, SatDump every cycle).
    float seen = std::fabs(*az_target - az_.status().position_deg);
    if (el_deg) seen = std::fmax(seen, std::fabs(*el_deg - el_.status().position_deg));
    lead_.note_client_error(seen);
    az_plan = lead_axis(az_, *az_target, lead_.az);
    if (el_deg) el_plan = lead_axis(el_, *el_deg, lead_.el);
    if (az_plan.hold || el_plan.hold || az_plan.aim_deg != *az_target ||
        (el_deg && el_plan.aim_deg != *el_deg))
      lead_.count_led();
  } else if (az_target) {
    lead_.reset();
    lead_.az.note(*az_target);
    if (el_deg) lead_.el.note(*el_deg);
  }
  if (az_target) {
    if (!az_plan.hold) {
      const Error e = az_.go_to(az_plan.aim_deg);
      if (e != Error::kOk) return e;
    }
    stream_.accept(step, *az_deg, *az_target, source, now_);
    if (shift_deg != 0.0f) stream_.count_resolved();
    az_shift_deg_ = shift_deg;
  }
  if (el_deg && !el_plan.hold) {
    const Error e = el_.go_to(el_plan.aim_deg);
    if (e != Error::kOk) return e;
  }
  if (az_target || el_deg) mode_ = Mode::kGoto;
  return Error::kOk;
}

StreamLead::Plan Controller::lead_axis(const Axis& axis, float sent_deg,
                                       const StreamLead::Axis& stream) const {
  const AxisStatus& s = axis.status();
  const AxisConfig& c = axis.config();
  const bool at_rest = s.state == AxisState::kIdle && !s.has_target;
  // An endless axis reads 0..360 and its stream wraps at north: not led.
  if (c.continuous) return StreamLead::plan(sent_deg, s.position_deg, 0, at_rest, 0.0f, 0.0f, 0.0f);
  return StreamLead::plan(sent_deg, s.position_deg, stream.steady_dir(), at_rest,
                          lead_.band_deg(stream, c.tolerance_deg), c.min_deg, c.max_deg);
}

Error Controller::move(AxisId axis, Direction dir, int speed_pct, Millis deadman_ms) {
  if (dir != Direction::kNone && wind_.refusing()) return Error::kStowed;
  note_command();
  stream_.interrupt();
  if (axis == AxisId::kEl && !has_el_) return Error::kNotSupported;
  if (speed_pct != -1 && (speed_pct < 1 || speed_pct > 100)) return Error::kOutOfRange;
  Axis& a = axis == AxisId::kAz ? az_ : el_;
  if (speed_pct != -1) a.set_speed_pct(speed_pct);
  const Error e = a.jog(dir, deadman_ms > 0 ? now_ + deadman_ms : 0);
  if (e == Error::kOk && dir != Direction::kNone) mode_ = Mode::kManual;
  return e;
}

void Controller::stop() {
  // STOP always works, a stow's move included; that stow is not commanded
  // again by itself this windy spell (controller_wind.cpp).
  if (stow_pending_ || mode_ == Mode::kStow) wind_.stopped_by_operator();
  stow_pending_ = false;
  if (commissioning_.running()) commissioning_.abort(commissioned_axis(), "STOP");
  end_recognition(RecognitionEnd::kStop);
  note_command();
  stream_.interrupt();
  az_.stop();
  el_.stop();
  mode_ = Mode::kIdle;
}

Error Controller::park() {
  end_recognition(RecognitionEnd::kPark);
  const float park_az = settings_.f(Id::kParkAzDeg);
  std::optional<float> park_el;
  if (has_el_) park_el = settings_.f(Id::kParkElDeg);
  const Error e = go_to(park_az, park_el, AzTarget::kUnwrapped);
  if (e == Error::kOk) mode_ = Mode::kPark;
  return e;
}

Error Controller::reset() {
  stop();
  if (estop_active_) return Error::kFaulted;  // released first, then RESET
  // RESET carries on: a stow that a fault (or STOP) cut short goes on.
  if (wind_.refusing()) stow_pending_ = wind_.restow();
  az_.clear_fault();
  el_.clear_fault();
  count_faults();  // a fault that comes back after the reset counts again
  speed_pct_ = settings_.i(Id::kSpeedPct);
  az_.set_speed_pct(speed_pct_);
  el_.set_speed_pct(speed_pct_);
  return Error::kOk;
}

Error Controller::set_speed_pct(int pct) {
  if (pct < 1 || pct > 100) return Error::kOutOfRange;
  end_track();
  speed_pct_ = pct;
  az_.set_speed_pct(pct);
  el_.set_speed_pct(pct);
  return Error::kOk;
}

Limits Controller::limits() const {
  Limits l;
  const AxisConfig& a = az_.config();
  l.az_min_deg = a.continuous ? 0.0f : a.min_deg;
  l.az_max_deg = a.continuous ? 360.0f : a.max_deg;
  l.az_continuous = a.continuous;
  l.has_el = has_el_;
  if (has_el_) {
    l.el_min_deg = el_.config().min_deg;
    l.el_max_deg = el_.config().max_deg;
  } else {
    l.el_min_deg = 0.0f;
    l.el_max_deg = 0.0f;
  }
  return l;
}

RotatorStatus Controller::status() const {
  RotatorStatus s;
  s.az = az_.status();
  if (has_el_) s.el = el_.status();
  s.mode = mode_;
  s.speed_pct = speed_pct_;
  s.limits = limits();
  s.wind_state = wind_.state();
  s.wind_has_speed = wind_.has_speed();
  s.wind_speed_mps = wind_.speed_mps();
  s.wind_stows = wind_.stows();
  s.wind_overrides = wind_.overrides();
  for (std::size_t n = 0; n < care::kWindRejectKinds; ++n)
    s.wind_rejected += wind_.rejected(static_cast<care::WindReject>(n));
  return s;
}

}  // namespace rotord

namespace rotord {

Error Controller::commission(const Commissioning::Request& request, const char** why) {
  if (request.axis == AxisId::kEl && !has_el_) {
    *why = "this rotator has no elevation axis";
    return Error::kNotSupported;
  }
  if (tracker_.armed()) {
    *why = "a track is running: stop it first";
    return Error::kBusy;
  }
  if (wind_.refusing()) {
    *why = "stowed for the wind: wait for calm or override the stow";
    return Error::kStowed;
  }
  // The known bearing turns the zero from the reading now, which is in the
  // frame of the settings applied at the last tick: a zero, a direction or
  // an offset saved since then would be counted twice. The next tick
  // applies them and reads again.
  if (request.step == Commissioning::Step::kBearing && settings_.revision() != applied_revision_) {
    *why = "settings just changed: retry";
    return Error::kBusy;
  }
  stop();
  // Settings accepted just now (a swap) are the frame the run starts from.
  if (settings_.revision() != applied_revision_) apply_settings();
  Axis& axis = request.axis == AxisId::kEl ? el_ : az_;
  return commissioning_.start(request, axis, why);
}

settings::Rejection Controller::accept_commissioning() {
  if (commissioning_.state() != Commissioning::State::kDone)
    return {Error::kInvalidArgument, "no finished self-commissioning to accept"};
  return commissioning_.apply_proposal(settings_);
}

}  // namespace rotord
