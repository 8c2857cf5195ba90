#include "rotator/tracker.hpp"

#include <cmath>
#include <cstring>

#include "motion/angles.hpp"

namespace rotord {

using settings::Id;
using tracking::Sgp4Error;
using tracking::TargetKind;

namespace {

/// How far ahead a pass is searched for ("next pass").
constexpr std::int64_t kSearchWindowMs = 48LL * 3600 * 1000;
/// The longest pass followed in one track (a geostationary satellite is
/// always up; the Sun is up for up to a day near the poles).
constexpr std::int64_t kLongestPassMs = 24LL * 3600 * 1000;
/// Pre-positioning starts this much earlier than the slew needs, plus half
/// the slew time again (a slower slew than measured, a reversal dead time).
constexpr std::int64_t kPrepositionMarginMs = 15000;
/// The plan keeps the azimuth this far inside the travel at least.
constexpr float kPlanMarginDeg = 2.0f;

}  // namespace

const char* track_phase_name(TrackPhase phase) {
  switch (phase) {
    case TrackPhase::kOff:
      return "off";
    case TrackPhase::kFinding:
      return "finding";
    case TrackPhase::kPlanning:
      return "planning";
    case TrackPhase::kWaiting:
      return "waiting";
    case TrackPhase::kPrepositioning:
      return "prepositioning";
    case TrackPhase::kTracking:
      return "tracking";
    case TrackPhase::kHolding:
      return "holding";
    case TrackPhase::kDone:
      return "done";
    case TrackPhase::kFailed:
      return "failed";
  }
  return "?";
}

const char* track_error_text(TrackError error) {
  switch (error) {
    case TrackError::kOk:
      return "ok";
    case TrackError::kNoClock:
      return "the time (UTC) is not known yet; tracking needs a valid clock";
    case TrackError::kClockUnsynced:
      return "the computer's clock is not synchronized with a time server (NTP), and "
             "satellite positions need the right time: let it set its clock (timedatectl "
             "set-ntp true, a reachable NTP server), or, if you know the clock is right, turn "
             "on time.trust_system_clock in Settings";
    case TrackError::kBadElements:
      return "SGP4 cannot use these elements";
    case TrackError::kPropagation:
      return "SGP4 cannot propagate this object over the pass (decayed?)";
    case TrackError::kBelowHorizon:
      return "the target is below track.min_el_deg now; track it at its next pass";
    case TrackError::kNoPass:
      return "no pass above track.min_el_deg within 48 hours";
    case TrackError::kOutOfRange:
      return "outside the travel";
    case TrackError::kNotSupported:
      return "this rotator has no elevation axis";
    case TrackError::kFaulted:
      return "an axis has a latched fault: clear it first";
    case TrackError::kNoTarget:
      return "nothing to track";
    case TrackError::kStowed:
      return "stowed for the wind: moves are refused until it is calm (wind.calm_min) or an "
             "operator overrides the stow";
    case TrackError::kNoStation:
      return "the station's position is not set: enter the antenna's latitude and longitude "
             "(station.lat_deg, station.lon_deg) in Settings; passes and pointing would "
             "otherwise be computed for 0 N 0 E";
  }
  return "?";
}

void Tracker::fail(TrackError error, Sgp4Error sgp4) {
  status_.phase = TrackPhase::kFailed;
  status_.error = error;
  status_.sgp4_error = sgp4;
  status_.have_target = false;
}

void Tracker::cancel() {
  if (status_.armed()) status_.phase = TrackPhase::kOff;
  status_.have_target = false;
}

TrackError Tracker::start(const TrackRequest& request, std::int64_t utc_ms,
                          const tracking::Observer& observer, const settings::Settings& values,
                          Axis& az, Axis* el) {
  TrackStatus fresh;
  // What was learned about the axes outlives one track.
  for (int n = 0; n < 2; ++n) {
    fresh.lag_ms[n] = status_.lag_ms[n];
    fresh.speed_deg_s[n] = status_.speed_deg_s[n];
  }
  status_ = fresh;
  status_.kind = request.kind;
  observer_ = observer;
  when_ = request.when;
  after_los_ = values.i(Id::kTrackAfterLos);
  min_el_deg_ = values.f(Id::kTrackMinElDeg);
  az_shift_deg_ = 0.0f;
  planned_unwind_done_ = false;
  return_az_deg_ = az.status().position_deg;
  return_el_deg_ = el != nullptr ? el->status().position_deg : 0.0f;
  if (az.status().fault != AxisFault::kNone ||
      (el != nullptr && el->status().fault != AxisFault::kNone))
    return status_.error = TrackError::kFaulted;
  // First use: the configured speed and a lag from the start sequence; the
  // measurements take over from the first moves.
  Axis* axes[2] = {&az, el};
  for (int n = 0; n < 2; ++n) {
    if (axes[n] == nullptr) continue;
    const AxisConfig& c = axes[n]->config();
    AxisFollow& f = follow_[n];
    if (status_.speed_deg_s[n] <= 0.0f) {
      f.speed_deg_s = c.speed_deg_s;
      f.lag_ms = static_cast<float>(c.dir_settle_ms + (c.has_brake ? c.brake_release_ms : 0) +
                                    c.soft_ms / 2 + 200);
    }
    f.awaiting_motion = false;
    f.was_moving = false;
  }

  if (request.kind == TargetKind::kNone) {
    // A fixed direction: the compass azimuth on the turn that turns least.
    const AxisConfig& c = az.config();
    std::optional<float> az_target;
    if (c.continuous) {
      if (request.az_deg >= 0.0f && request.az_deg <= 360.0f) az_target = request.az_deg;
    } else if (request.az_deg >= 0.0f && request.az_deg <= 360.0f) {
      az_target = choose_unwrapped_az(request.az_deg, az.status().position_deg, c.min_deg,
                                      c.max_deg, false);
    }
    if (!az_target) return status_.error = TrackError::kOutOfRange;
    if (el == nullptr && request.el_deg != 0.0f) return status_.error = TrackError::kNotSupported;
    if (el != nullptr &&
        (request.el_deg < el->config().min_deg || request.el_deg > el->config().max_deg))
      return status_.error = TrackError::kOutOfRange;
    std::strncpy(status_.name, "fixed", sizeof(status_.name) - 1);
    status_.target_az_deg = *az_target;
    status_.target_el_deg = request.el_deg;
    status_.sky_az_deg = request.az_deg;
    status_.sky_el_deg = request.el_deg;
    status_.have_target = true;
    status_.phase = TrackPhase::kHolding;
    az.go_to(*az_target);
    if (el != nullptr) el->go_to(request.el_deg);
    return TrackError::kOk;
  }

  if (request.kind == TargetKind::kSatellite) {
    const Sgp4Error e = target_.set_satellite(request.tle);
    if (e != Sgp4Error::kOk) {
      status_.sgp4_error = e;
      return status_.error = TrackError::kBadElements;
    }
    std::memcpy(status_.name, request.tle.name, sizeof(status_.name));
    status_.catalog = request.tle.catalog;
  } else {
    target_.set_body(request.kind == TargetKind::kSun ? tracking::Body::kSun
                                                      : tracking::Body::kMoon);
    std::strncpy(status_.name, request.kind == TargetKind::kSun ? "Sun" : "Moon",
                 sizeof(status_.name) - 1);
  }
  tracking::LookAngles look;
  const Sgp4Error e = target_.look(utc_ms, observer_, look);
  if (e != Sgp4Error::kOk) {
    status_.sgp4_error = e;
    return status_.error = TrackError::kPropagation;
  }
  status_.sky_az_deg = static_cast<float>(look.az_deg);
  status_.sky_el_deg = static_cast<float>(look.el_deg);
  if (when_ == TrackWhen::kNow && look.el_deg < min_el_deg_)
    return status_.error = TrackError::kBelowHorizon;
  finder_.start(target_, observer_, utc_ms, utc_ms + kSearchWindowMs, min_el_deg_);
  status_.phase = TrackPhase::kFinding;
  return TrackError::kOk;
}

void Tracker::find(std::int64_t utc_ms) {
  switch (finder_.step(budget_)) {
    case tracking::PassFinder::Status::kSearching:
      return;
    case tracking::PassFinder::Status::kDone:
      return fail(TrackError::kNoPass);
    case tracking::PassFinder::Status::kError:
      return fail(TrackError::kPropagation, finder_.error());
    case tracking::PassFinder::Status::kFound:
      break;
  }
  status_.pass = finder_.pass();
  status_.have_pass = true;
  tracking::Pass& p = status_.pass;
  if (p.los_ms - p.aos_ms > kLongestPassMs) {
    p.los_ms = p.aos_ms + kLongestPassMs;
    p.los_clipped = true;
  }
  table_.begin(p.aos_ms > utc_ms ? p.aos_ms : utc_ms, p.los_ms);
  status_.phase = TrackPhase::kPlanning;
}

void Tracker::plan(std::int64_t utc_ms, Axis& az, Axis* el) {
  for (int n = 0; n < budget_ && !table_.complete(); ++n) {
    tracking::LookAngles look;
    const Sgp4Error e = target_.look(table_.next_time(), observer_, look);
    if (e != Sgp4Error::kOk) return fail(TrackError::kPropagation, e);
    table_.add(look);
  }
  if (!table_.complete()) return;
  // A path the rotator can follow (each axis at 85 % of its measured speed:
  // its starts and stops take some of it).
  table_.limit_rates(0.85f * follow_[0].speed_deg_s,
                     el != nullptr ? 0.85f * follow_[1].speed_deg_s : 1000.0f);
  tracking::Travel travel;
  const AxisConfig& ac = az.config();
  travel.az_min_deg = ac.min_deg;
  travel.az_max_deg = ac.max_deg;
  travel.az_continuous = ac.continuous;
  travel.has_el = el != nullptr;
  if (el != nullptr) {
    travel.el_min_deg = el->config().min_deg;
    travel.el_max_deg = el->config().max_deg;
  }
  const float az_now = az.status().position_deg;
  const float el_now = el != nullptr ? el->status().position_deg : 0.0f;
  // A pass no turn holds whole unwinds once, where the satellite is lowest
  // while the antenna turns round (360 deg at the measured speed).
  const float az_speed = follow_[0].speed_deg_s > 0.5f ? follow_[0].speed_deg_s : 0.5f;
  const float unwind_s = 360.0f / az_speed + follow_[0].lag_ms / 1000.0f;
  status_.plan = tracking::choose_plan(table_, travel, az_now, el_now, kPlanMarginDeg, unwind_s);
  status_.planned = true;
  // Pre-position in time for AOS at the speed measured so far.
  float az0 = 0.0f, el0 = 0.0f;
  position_now(table_.start_ms(), az0, el0);
  float slew_s = std::fabs(az0 - az_now) / follow_[0].speed_deg_s + follow_[0].lag_ms / 1000.0f;
  if (el != nullptr) {
    const float el_s =
        std::fabs(el0 - el_now) / follow_[1].speed_deg_s + follow_[1].lag_ms / 1000.0f;
    if (el_s > slew_s) slew_s = el_s;
  }
  status_.preposition_at_ms =
      table_.start_ms() - static_cast<std::int64_t>(slew_s * 1500.0f) - kPrepositionMarginMs;
  status_.phase = TrackPhase::kWaiting;
  (void)utc_ms;
}

void Tracker::position_now(std::int64_t utc_ms, float& az, float& el) const {
  tracking::plan_position(table_, status_.plan, utc_ms, az, el);
  az += az_shift_deg_;
}

float Tracker::inside_az(float az_deg, const Axis& axis) {
  const AxisConfig& c = axis.config();
  if (c.continuous || status_.plan.fits) return az_deg;
  // The plan holds at the travel's end while the pass is beyond it (that
  // loses less than an unwind): the antenna waits there for the pass to
  // come back or set.
  if (status_.plan.unwind_deg == 0.0f) {
    if (az_deg > c.max_deg - 0.5f) return c.max_deg - 0.5f;
    if (az_deg < c.min_deg + 0.5f) return c.min_deg + 0.5f;
    return az_deg;
  }
  // A planned unwind keeps the azimuth inside; past it, as a backstop, turn
  // the other way round once, where the pass leaves the travel.
  if (az_deg > c.max_deg - 0.5f) {
    az_shift_deg_ -= 360.0f;
    ++status_.unwinds;
    return az_deg - 360.0f;
  }
  if (az_deg < c.min_deg + 0.5f) {
    az_shift_deg_ += 360.0f;
    ++status_.unwinds;
    return az_deg + 360.0f;
  }
  return az_deg;
}

Tracker::Action Tracker::tick(Millis now, std::int64_t utc_ms, Axis& az, Axis* el) {
  if (!status_.armed()) return Action::kNone;
  if (az.status().fault != AxisFault::kNone ||
      (el != nullptr && el->status().fault != AxisFault::kNone)) {
    fail(TrackError::kFaulted);
    return Action::kFailed;
  }
  learn_axis(follow_[0], az, now);
  if (el != nullptr) learn_axis(follow_[1], *el, now);
  for (int n = 0; n < 2; ++n) {
    status_.lag_ms[n] = follow_[n].lag_ms;
    status_.speed_deg_s[n] = follow_[n].speed_deg_s;
  }
  switch (status_.phase) {
    case TrackPhase::kFinding:
      find(utc_ms);
      return status_.phase == TrackPhase::kFailed ? Action::kFailed : Action::kNone;
    case TrackPhase::kPlanning:
      plan(utc_ms, az, el);
      return status_.phase == TrackPhase::kFailed ? Action::kFailed : Action::kNone;
    case TrackPhase::kHolding: {
      // Hold the direction against wind and drift.
      const AxisStatus& s = az.status();
      const float az_error =
          az.config().continuous
              ? unwrap_near(status_.target_az_deg, s.position_deg) - s.position_deg
              : status_.target_az_deg - s.position_deg;
      if (!s.has_target && s.state == AxisState::kIdle &&
          std::fabs(az_error) > 2.0f * az.config().tolerance_deg)
        az.go_to(status_.target_az_deg);
      if (el != nullptr) {
        const AxisStatus& e = el->status();
        if (!e.has_target && e.state == AxisState::kIdle &&
            std::fabs(e.position_deg - status_.target_el_deg) > 2.0f * el->config().tolerance_deg)
          el->go_to(status_.target_el_deg);
      }
      return Action::kNone;
    }
    default:
      break;
  }
  // Waiting, pre-positioning or tracking: the plan is known.
  const tracking::Pass& p = status_.pass;
  if (utc_ms >= p.los_ms) {
    status_.phase = TrackPhase::kDone;
    status_.have_target = false;
    return after_los_ == 1 ? Action::kPark : (after_los_ == 2 ? Action::kReturn : Action::kNone);
  }
  float az_now = 0.0f, el_now = 0.0f;
  position_now(utc_ms, az_now, el_now);
  {
    float u = 0.0f, e = 0.0f;
    table_.at(utc_ms, u, e);
    status_.sky_az_deg = wrap_360(u);
    status_.sky_el_deg = e;
  }
  if (status_.phase == TrackPhase::kWaiting) {
    if (utc_ms < status_.preposition_at_ms) return Action::kNone;
    status_.phase = TrackPhase::kPrepositioning;
  }
  if (status_.phase == TrackPhase::kPrepositioning) {
    if (utc_ms < table_.start_ms()) {
      // To where the pass begins, at full speed, once (and again if a
      // correction is needed once it stands).
      float az0 = 0.0f, el0 = 0.0f;
      position_now(table_.start_ms(), az0, el0);
      status_.target_az_deg = az0;
      status_.target_el_deg = el0;
      status_.have_target = true;
      follow_axis(az, follow_[0], az0, az0, 0.0f, now, true);
      if (el != nullptr) follow_axis(*el, follow_[1], el0, el0, 0.0f, now, true);
      return Action::kNone;
    }
    status_.phase = TrackPhase::kTracking;
  }
  // Following. Each axis leads by its own measured lag.
  if (status_.plan.unwind_deg != 0.0f && !planned_unwind_done_ &&
      utc_ms >= status_.plan.unwind_at_ms) {
    planned_unwind_done_ = true;
    ++status_.unwinds;
  }
  az_now = inside_az(az_now, az);
  float az_lead = 0.0f, el_lead = 0.0f, az_next = 0.0f, el_next = 0.0f, unused = 0.0f;
  position_now(utc_ms + static_cast<std::int64_t>(follow_[0].lag_ms), az_lead, unused);
  position_now(utc_ms + 1000, az_next, el_next);
  status_.target_az_deg = az_now;
  status_.target_el_deg = el_now;
  status_.have_target = true;
  follow_axis(az, follow_[0], az_now, az_lead, az_next - az_now, now, false);
  if (el != nullptr) {
    position_now(utc_ms + static_cast<std::int64_t>(follow_[1].lag_ms), unused, el_lead);
    follow_axis(*el, follow_[1], el_now, el_lead, el_next - el_now, now, false);
  }
  return Action::kNone;
}

}  // namespace rotord
