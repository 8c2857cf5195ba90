#include "tracking/track_plan.hpp"

#include <cmath>

namespace rotord::tracking {

namespace {

/// The forward and backward speed-limited followers of `v`, averaged into `v`.
void limit_one(float* v, float* scratch, std::size_t n, float max_step) {
  if (n < 2 || !(max_step > 0.0f)) return;
  scratch[0] = v[0];
  for (std::size_t i = 1; i < n; ++i) {
    const float d = v[i] - scratch[i - 1];
    scratch[i] = scratch[i - 1] + (d > max_step ? max_step : (d < -max_step ? -max_step : d));
  }
  float back = v[n - 1];
  const float last = scratch[n - 1];
  v[n - 1] = 0.5f * (back + last);
  for (std::size_t i = n - 1; i-- > 0;) {
    const float d = v[i] - back;
    back += d > max_step ? max_step : (d < -max_step ? -max_step : d);
    v[i] = 0.5f * (back + scratch[i]);
  }
}

float wrap_180(float deg) {
  float d = std::fmod(deg, 360.0f);
  if (d > 180.0f) d -= 360.0f;
  if (d < -180.0f) d += 360.0f;
  return d;
}

}  // namespace

void PassTable::begin(std::int64_t start_ms, std::int64_t end_ms) {
  start_ms_ = start_ms;
  end_ms_ = end_ms < start_ms ? start_ms : end_ms;
  const std::int64_t span = end_ms_ - start_ms_;
  const auto intervals = static_cast<std::int64_t>(kCapacity - 1);
  step_ms_ = (span + intervals - 1) / intervals;
  if (step_ms_ < kMinStepMs) step_ms_ = kMinStepMs;
  count_ = 0;
}

void PassTable::add(const LookAngles& look) {
  if (count_ >= kCapacity) return;
  float az = static_cast<float>(look.az_deg);
  const float el = static_cast<float>(look.el_deg);
  if (count_ == 0) {
    az_lo_ = az_hi_ = az;
    el_lo_ = el_hi_ = el;
    az_path_ = el_path_ = 0.0f;
  } else {
    const float prev = az_[count_ - 1];
    float d = std::fmod(az - prev, 360.0f);
    if (d > 180.0f) d -= 360.0f;
    if (d < -180.0f) d += 360.0f;
    // Near the zenith the azimuth can swing almost 180 deg between samples;
    // its rate says which way it went.
    if (std::fabs(d) > 90.0f && (d > 0.0f) != (look.az_rate_deg_s > 0.0))
      d += d > 0 ? -360.0f : 360.0f;
    az = prev + d;
    az_path_ += std::fabs(d);
    el_path_ += std::fabs(el - el_[count_ - 1]);
    az_lo_ = std::fmin(az_lo_, az);
    az_hi_ = std::fmax(az_hi_, az);
    el_lo_ = std::fmin(el_lo_, el);
    el_hi_ = std::fmax(el_hi_, el);
  }
  az_[count_] = az;
  el_[count_] = el;
  ++count_;
}

void PassTable::limit_rates(float az_deg_s, float el_deg_s) {
  const float step_s = static_cast<float>(step_ms_) / 1000.0f;
  limit_one(az_, scratch_, count_, az_deg_s * step_s);
  limit_one(el_, scratch_, count_, el_deg_s * step_s);
  az_lo_ = az_hi_ = az_[0];
  el_lo_ = el_hi_ = el_[0];
  for (std::size_t i = 1; i < count_; ++i) {
    az_lo_ = std::fmin(az_lo_, az_[i]);
    az_hi_ = std::fmax(az_hi_, az_[i]);
    el_lo_ = std::fmin(el_lo_, el_[i]);
    el_hi_ = std::fmax(el_hi_, el_[i]);
  }
}

void PassTable::at(std::int64_t t_ms, float& az_unwrapped_deg, float& el_deg) const {
  if (count_ == 0) {
    az_unwrapped_deg = el_deg = 0.0f;
    return;
  }
  if (t_ms <= start_ms_) {
    az_unwrapped_deg = az_[0];
    el_deg = el_[0];
    return;
  }
  const std::int64_t offset = t_ms - start_ms_;
  const auto n = static_cast<std::size_t>(offset / step_ms_);
  if (n + 1 >= count_) {
    az_unwrapped_deg = az_[count_ - 1];
    el_deg = el_[count_ - 1];
    return;
  }
  const float f = static_cast<float>(offset - static_cast<std::int64_t>(n) * step_ms_) /
                  static_cast<float>(step_ms_);
  az_unwrapped_deg = az_[n] + (az_[n + 1] - az_[n]) * f;
  el_deg = el_[n] + (el_[n + 1] - el_[n]) * f;
}

PassPlan choose_plan(const PassTable& table, const Travel& travel, float az_now_deg,
                     float el_now_deg, float margin_deg) {
  PassPlan best;
  bool have = false;
  float best_excess = 1e9f;
  PassPlan fallback;
  for (const bool flip : {false, true}) {
    if (flip) {
      // el' = 180 - el must stay within the travel.
      if (!travel.has_el || 180.0f - table.el_lowest_deg() > travel.el_max_deg + 0.01f ||
          180.0f - table.el_highest_deg() < travel.el_min_deg - 0.01f)
        continue;
    }
    float first_az = 0.0f, first_el = 0.0f;
    table.at(table.start_ms(), first_az, first_el);
    const float base = flip ? 180.0f : 0.0f;
    const float el_start = flip ? 180.0f - first_el : first_el;
    const float el_cost = travel.has_el ? std::fabs(el_start - el_now_deg) : 0.0f;
    if (travel.az_continuous) {
      PassPlan p;
      p.flip = flip;
      // Any turn: the one that starts nearest.
      const float start = first_az + base;
      p.az_offset_deg = (az_now_deg + wrap_180(start - az_now_deg)) - start;
      p.preposition_deg = std::fabs(wrap_180(start - az_now_deg)) + el_cost;
      p.margin_deg = 1e6f;
      if (!have || p.preposition_deg < best.preposition_deg - 0.5f) {
        best = p;
        have = true;
      }
      continue;
    }
    for (int k = -3; k <= 3; ++k) {
      const float offset = 360.0f * static_cast<float>(k);
      const float lo = table.az_lowest_deg() + base + offset;
      const float hi = table.az_highest_deg() + base + offset;
      PassPlan p;
      p.flip = flip;
      p.az_offset_deg = offset;
      p.preposition_deg = std::fabs(first_az + base + offset - az_now_deg) + el_cost;
      p.margin_deg = std::fmin(lo - travel.az_min_deg, travel.az_max_deg - hi);
      if (p.margin_deg < margin_deg) {
        // Out of the travel somewhere: remembered only for when no plan fits.
        const float excess =
            std::fmax(0.0f, travel.az_min_deg - lo) + std::fmax(0.0f, hi - travel.az_max_deg);
        const bool starts_inside = first_az + base + offset >= travel.az_min_deg &&
                                   first_az + base + offset <= travel.az_max_deg;
        if (starts_inside && excess < best_excess) {
          best_excess = excess;
          fallback = p;
          fallback.fits = false;
        }
        continue;
      }
      const bool cheaper = p.preposition_deg < best.preposition_deg - 0.5f;
      const bool tie = std::fabs(p.preposition_deg - best.preposition_deg) <= 0.5f;
      const bool better_tie = tie && ((!p.flip && best.flip) ||
                                      (p.flip == best.flip && p.margin_deg > best.margin_deg));
      if (!have || cheaper || better_tie) {
        best = p;
        have = true;
      }
    }
  }
  return have ? best : fallback;
}

void plan_position(const PassTable& table, const PassPlan& plan, std::int64_t t_ms, float& az_deg,
                   float& el_deg) {
  float az = 0.0f, el = 0.0f;
  table.at(t_ms, az, el);
  az_deg = az + (plan.flip ? 180.0f : 0.0f) + plan.az_offset_deg;
  el_deg = plan.flip ? 180.0f - el : el;
}

}  // namespace rotord::tracking
