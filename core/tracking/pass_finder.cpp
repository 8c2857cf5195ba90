#include "tracking/pass_finder.hpp"

#include <cmath>

namespace rotord::tracking {
namespace {

/// AOS, LOS and culmination are refined to this.
constexpr std::int64_t kResolutionMs = 100;
constexpr double kGolden = 0.6180339887498949;

std::int64_t golden_offset(std::int64_t a, std::int64_t b) {
  return static_cast<std::int64_t>(std::llround(static_cast<double>(b - a) * kGolden));
}

}  // namespace

double PassFinder::default_scan_step_s(const SkyTarget& target) {
  if (target.kind() != TargetKind::kSatellite) return 300.0;
  const double period_s = 86400.0 / target.tle().mean_motion_rev_day;
  const double step = period_s / 300.0;
  return step < 5.0 ? 5.0 : (step > 600.0 ? 600.0 : step);
}

void PassFinder::start(SkyTarget& target, const Observer& observer, std::int64_t from_ms,
                       std::int64_t to_ms, double min_el_deg, double scan_step_s) {
  target_ = &target;
  observer_ = observer;
  from_ms_ = from_ms;
  to_ms_ = to_ms < from_ms ? from_ms : to_ms;
  min_el_deg_ = min_el_deg;
  if (scan_step_s <= 0.0) scan_step_s = default_scan_step_s(target);
  step_ms_ = static_cast<std::int64_t>(std::llround(scan_step_s * 1000.0));
  if (step_ms_ < 1) step_ms_ = 1;
  phase_ = Phase::kScan;
  pending_ = Status::kSearching;
  error_ = Sgp4Error::kOk;
  t_ = from_ms;
  have_prev_ = false;
  in_pass_ = false;
  pass_ = Pass{};
}

PassFinder::Status PassFinder::step(int max_evaluations) {
  for (int n = 0; n < max_evaluations; ++n) {
    switch (phase_) {
      case Phase::kScan:
        scan_once();
        break;
      case Phase::kAos:
      case Phase::kLos:
        bisect_once();
        break;
      case Phase::kCulmination:
      case Phase::kRateBefore:
      case Phase::kRateAfter:
        golden_once();
        break;
      case Phase::kIdle:
      case Phase::kDone:
        return Status::kDone;
      case Phase::kError:
        return Status::kError;
    }
    if (pending_ == Status::kFound) {
      pending_ = Status::kSearching;
      return Status::kFound;
    }
    if (phase_ == Phase::kError) return Status::kError;
  }
  return phase_ == Phase::kDone ? Status::kDone : Status::kSearching;
}

bool PassFinder::evaluate(std::int64_t t, LookAngles& look) {
  error_ = target_->look(t, observer_, look);
  if (error_ == Sgp4Error::kOk) return true;
  phase_ = Phase::kError;
  return false;
}

void PassFinder::note_in_pass(std::int64_t t, const LookAngles& look) {
  pass_.max_az_rate_deg_s = std::fmax(pass_.max_az_rate_deg_s, std::fabs(look.az_rate_deg_s));
  pass_.max_el_rate_deg_s = std::fmax(pass_.max_el_rate_deg_s, std::fabs(look.el_rate_deg_s));
  if (look.el_deg > best_look_.el_deg) {
    best_look_ = look;
    best_t_ = t;
  }
}

void PassFinder::open_pass(std::int64_t t, const LookAngles& look, bool clipped) {
  pass_ = Pass{};
  pass_.aos_ms = t;
  pass_.aos_az_deg = look.az_deg;
  pass_.aos_clipped = clipped;
  best_look_ = look;
  best_t_ = t;
  note_in_pass(t, look);
  in_pass_ = true;
}

void PassFinder::scan_once() {
  LookAngles look;
  if (!evaluate(t_, look)) return;
  const bool up = look.el_deg >= min_el_deg_;
  if (in_pass_ && !up) {
    // Set between the previous sample and this one.
    lo_ = prev_t_;
    hi_ = t_;
    edge_look_ = prev_look_;
    phase_ = Phase::kLos;
    return;
  }
  if (!in_pass_ && up) {
    if (!have_prev_) {
      open_pass(t_, look, true);
    } else {
      lo_ = prev_t_;
      hi_ = t_;
      edge_look_ = look;
      phase_ = Phase::kAos;
      return;
    }
  } else if (in_pass_) {
    note_in_pass(t_, look);
  }
  if (t_ >= to_ms_) {
    if (in_pass_) {
      pass_.los_ms = to_ms_;
      pass_.los_az_deg = look.az_deg;
      pass_.los_clipped = true;
      begin_culmination();
    } else {
      phase_ = Phase::kDone;
    }
    return;
  }
  prev_t_ = t_;
  prev_look_ = look;
  have_prev_ = true;
  t_ = t_ + step_ms_ < to_ms_ ? t_ + step_ms_ : to_ms_;
}

void PassFinder::bisect_once() {
  const bool rising = phase_ == Phase::kAos;
  if (hi_ - lo_ <= kResolutionMs) {
    if (rising) {
      // AOS is the first time found above; scan on from the sample after it.
      open_pass(hi_, edge_look_, false);
      phase_ = Phase::kScan;
    } else {
      pass_.los_ms = lo_;
      pass_.los_az_deg = edge_look_.az_deg;
      t_ = hi_;  // below: the scan resumes from here after the culmination
      begin_culmination();
    }
    return;
  }
  const std::int64_t mid = lo_ + (hi_ - lo_) / 2;
  LookAngles look;
  if (!evaluate(mid, look)) return;
  const bool up = look.el_deg >= min_el_deg_;
  if (up) note_in_pass(mid, look);
  if (up == rising) {
    hi_ = mid;
    if (rising) edge_look_ = look;
  } else {
    lo_ = mid;
    if (!rising) edge_look_ = look;
  }
}

void PassFinder::begin_culmination() {
  begin_golden(Phase::kCulmination,
               best_t_ - step_ms_ > pass_.aos_ms ? best_t_ - step_ms_ : pass_.aos_ms,
               best_t_ + step_ms_ < pass_.los_ms ? best_t_ + step_ms_ : pass_.los_ms);
}

void PassFinder::begin_golden(Phase phase, std::int64_t a, std::int64_t b) {
  ga_ = a;
  gb_ = b;
  golden_points_ = 0;
  phase_ = phase;
}

double PassFinder::objective(const LookAngles& look) const {
  return phase_ == Phase::kCulmination ? look.el_deg : std::fabs(look.el_rate_deg_s);
}

void PassFinder::golden_done() {
  if (phase_ == Phase::kCulmination) {
    begin_golden(Phase::kRateBefore, pass_.aos_ms, best_t_);
  } else if (phase_ == Phase::kRateBefore) {
    begin_golden(Phase::kRateAfter, best_t_, pass_.los_ms);
  } else {
    emit();
  }
}

void PassFinder::golden_once() {
  // Maximises objective() over [ga_, gb_] (unimodal there) to kResolutionMs;
  // every evaluation also counts for the pass's maxima.
  LookAngles look;
  if (gb_ - ga_ <= kResolutionMs) {
    const std::int64_t mid = ga_ + (gb_ - ga_) / 2;
    if (!evaluate(mid, look)) return;
    note_in_pass(mid, look);
    golden_done();
    return;
  }
  std::int64_t t;
  bool inner_c;  // the new point is the lower inner point c (else d)
  if (golden_points_ == 0) {
    t = gc_ = gb_ - golden_offset(ga_, gb_);
    inner_c = true;
  } else if (golden_points_ == 1) {
    t = gd_ = ga_ + golden_offset(ga_, gb_);
    inner_c = false;
  } else if (fc_ > fd_) {
    gb_ = gd_;
    gd_ = gc_;
    fd_ = fc_;
    t = gc_ = gb_ - golden_offset(ga_, gb_);
    inner_c = true;
  } else {
    ga_ = gc_;
    gc_ = gd_;
    fc_ = fd_;
    t = gd_ = ga_ + golden_offset(ga_, gb_);
    inner_c = false;
  }
  if (!evaluate(t, look)) return;
  note_in_pass(t, look);
  const double f = objective(look);
  if (inner_c) {
    fc_ = f;
  } else {
    fd_ = f;
  }
  if (golden_points_ < 2) ++golden_points_;
}

void PassFinder::emit() {
  pass_.max_el_ms = best_t_;
  pass_.max_el_deg = best_look_.el_deg;
  pass_.max_el_az_deg = best_look_.az_deg;
  pending_ = Status::kFound;
  in_pass_ = false;
  if (pass_.los_clipped || t_ > to_ms_) {
    phase_ = Phase::kDone;
    return;
  }
  // Resume the scan at the first sample found below (t_), with it as previous.
  have_prev_ = false;
  phase_ = Phase::kScan;
  // The sample at t_ is below: step from it without treating the next "up" as
  // a pass already in progress.
  LookAngles below;
  below.el_deg = min_el_deg_ - 1.0;
  prev_t_ = t_;
  prev_look_ = below;
  have_prev_ = true;
  t_ = t_ + step_ms_ < to_ms_ ? t_ + step_ms_ : to_ms_;
  if (prev_t_ >= to_ms_) phase_ = Phase::kDone;
}

}  // namespace rotord::tracking
