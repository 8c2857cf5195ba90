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

namespace {

/// The best split of a pass that fits no turn whole: samples before `i` on
/// the turn `offset`, from `i` on on `offset + turn`, each part `margin`
/// inside the travel. The prefix that fits ends at some sample and the
/// suffix that fits begins at some sample, so the feasible splits are one
/// interval; within it the split whose unwind window (`window` samples)
/// sees the lowest elevation wins. No arrays: the Pico plans on its stack.
bool best_split(const PassTable& t, float base, float offset, float turn, const Travel& travel,
                float margin, std::size_t window, std::size_t peak, std::size_t& split,
                float& cost) {
  const std::size_t n = t.size();
  const float lo_ok = travel.az_min_deg + margin;
  const float hi_ok = travel.az_max_deg - margin;
  // Longest prefix inside on `offset`: samples [0, prefix) fit.
  std::size_t prefix = 0;
  while (prefix < n) {
    const float a = t.az_sample(prefix) + base + offset;
    if (a < lo_ok || a > hi_ok) break;
    ++prefix;
  }
  // Longest suffix inside on `offset + turn`: samples [suffix, n) fit.
  std::size_t suffix = n;
  while (suffix > 0) {
    const float a = t.az_sample(suffix - 1) + base + offset + turn;
    if (a < lo_ok || a > hi_ok) break;
    --suffix;
  }
  // A split at i needs i <= prefix and i >= suffix; i = 0 or n is no unwind.
  const std::size_t first = suffix < 1 ? 1 : suffix;
  const std::size_t last = prefix > n - 1 ? n - 1 : prefix;
  if (first > last) return false;
  bool found = false;
  for (std::size_t i = first; i <= last; ++i) {
    // The elevation is one hump: the highest in [i, i + window] is the
    // peak when inside, else the higher end.
    const std::size_t end = i + window < n ? i + window : n - 1;
    const float c =
        peak >= i && peak <= end ? t.el_sample(peak) : std::fmax(t.el_sample(i), t.el_sample(end));
    if (!found || c < cost) {
      found = true;
      cost = c;
      split = i;
    }
  }
  return found;
}

/// What a plan that holds at the travel's ends (instead of unwinding) loses:
/// the integral of the squared pointing error (deg^2 s), the azimuth beyond
/// the end seen at the satellite's elevation.
float held_cost(const PassTable& t, float base, float offset, const Travel& travel, float margin) {
  const float step_s = static_cast<float>(t.step_ms()) / 1000.0f;
  float cost = 0.0f;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const float a = t.az_sample(i) + base + offset;
    const float beyond =
        std::fmax(0.0f, std::fmax(travel.az_min_deg + margin - a, a - travel.az_max_deg + margin));
    const float off = beyond * std::cos(t.el_sample(i) * 0.017453292f);
    cost += off * off * step_s;
  }
  return cost;
}

/// What an unwind loses in the same measure: for its whole duration the
/// azimuth is off by 0..180 deg, about 90 on average.
constexpr float kUnwindCostPerS = 90.0f * 90.0f;

}  // namespace

PassPlan choose_plan(const PassTable& table, const Travel& travel, float az_now_deg,
                     float el_now_deg, float margin_deg, float unwind_s) {
  PassPlan best;
  bool have = false;
  float best_excess = 1e9f;
  float best_held = 1e30f;
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
        const float held = held_cost(table, base, offset, travel, margin_deg);
        const bool less = held < best_held - 1.0f ||
                          (std::fabs(held - best_held) <= 1.0f && excess < best_excess);
        if (starts_inside && less) {
          best_excess = excess;
          best_held = held;
          fallback = p;
          fallback.fits = false;
          fallback.held_cost = held;
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
  if (have) return best;
  if (unwind_s <= 0.0f || travel.az_continuous || table.size() < 2) return fallback;
  // No turn holds the pass whole: unwind once, where it loses least.
  std::size_t peak = 0;
  for (std::size_t i = 1; i < table.size(); ++i)
    if (table.el_sample(i) > table.el_sample(peak)) peak = i;
  const auto window =
      static_cast<std::size_t>(unwind_s * 1000.0f / static_cast<float>(table.step_ms())) + 1;
  bool split_found = false;
  float best_cost = 0.0f, best_prep = 0.0f;
  PassPlan split_plan;
  for (const bool flip : {false, true}) {
    if (flip && (!travel.has_el || 180.0f - table.el_lowest_deg() > travel.el_max_deg + 0.01f ||
                 180.0f - table.el_highest_deg() < travel.el_min_deg - 0.01f))
      continue;
    const float base = flip ? 180.0f : 0.0f;
    for (int k = -3; k <= 3; ++k) {
      const float offset = 360.0f * static_cast<float>(k);
      for (const float turn : {-360.0f, 360.0f}) {
        std::size_t at = 0;
        float cost = 0.0f;
        // The split needs less room than a whole plan: the old reactive
        // unwind kept 0.5 deg, and a 360 deg rotator has none to spare.
        if (!best_split(table, base, offset, turn, travel, std::fmin(margin_deg, 0.5f), window,
                        peak, at, cost))
          continue;
        const float el_start = flip ? 180.0f - table.el_sample(0) : table.el_sample(0);
        const float prep = std::fabs(table.az_sample(0) + base + offset - az_now_deg) +
                           (travel.has_el ? std::fabs(el_start - el_now_deg) : 0.0f);
        // Lower elevation first; within a degree, the shorter way to AOS.
        const bool better = !split_found || cost < best_cost - 1.0f ||
                            (std::fabs(cost - best_cost) <= 1.0f && prep < best_prep);
        if (!better) continue;
        split_found = true;
        best_cost = cost;
        best_prep = prep;
        split_plan = PassPlan{};
        split_plan.flip = flip;
        split_plan.az_offset_deg = offset;
        split_plan.fits = false;
        split_plan.preposition_deg = prep;
        split_plan.margin_deg = margin_deg;
        split_plan.unwind_deg = turn;
        split_plan.unwind_at_ms =
            table.start_ms() + static_cast<std::int64_t>(at) * table.step_ms();
        split_plan.unwind_el_deg = cost;
      }
    }
  }
  // Holding at the end loses the pass's far end (low, usually); an unwind
  // loses the whole turn round. The one that loses less.
  return split_found && unwind_s * kUnwindCostPerS < fallback.held_cost ? split_plan : fallback;
}

void plan_position(const PassTable& table, const PassPlan& plan, std::int64_t t_ms, float& az_deg,
                   float& el_deg) {
  float az = 0.0f, el = 0.0f;
  table.at(t_ms, az, el);
  az_deg = az + (plan.flip ? 180.0f : 0.0f) + plan.az_offset_deg;
  if (plan.unwind_deg != 0.0f && t_ms >= plan.unwind_at_ms) az_deg += plan.unwind_deg;
  el_deg = plan.flip ? 180.0f - el : el;
}

}  // namespace rotord::tracking
