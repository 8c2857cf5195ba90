#pragma once
#include <cstddef>
#include <cstdint>

#include "tracking/observer.hpp"

namespace rotord::tracking {

/// The travel a rotator may use, as the planner needs it (and as the
/// protocols report it: rotord::Limits in rotator/controller.hpp is this type).
struct Travel {
  float az_min_deg = 0.0f;
  float az_max_deg = 360.0f;
  bool az_continuous = false;
  bool has_el = false;
  float el_min_deg = 0.0f;
  float el_max_deg = 90.0f;
};

/// A whole pass sampled on a fixed time grid before it starts, so that the
/// wrap and flip are chosen once for all of it and the follow phase only
/// interpolates (no SGP4 in the control tick). The azimuth is unwrapped
/// continuously from the first sample (a pass through north goes 350, 370,
/// ..., never back to 10), so its extent says which turn of the travel holds
/// it. Fixed capacity, no heap: 8 KB.
class PassTable {
 public:
  static constexpr std::size_t kCapacity = 1024;
  /// The finest grid: one sample a second (an ISS pass of 12 min: 720).
  static constexpr std::int64_t kMinStepMs = 1000;

  /// Samples from `start_ms` to `end_ms` (both included); the step is 1 s,
  /// or coarser when the span needs more than kCapacity samples.
  void begin(std::int64_t start_ms, std::int64_t end_ms);
  /// Whether samples are still missing, and the time of the next one.
  bool complete() const { return count_ > 0 && next_time() > end_ms_; }
  std::int64_t next_time() const {
    return start_ms_ + static_cast<std::int64_t>(count_) * step_ms_;
  }
  /// Adds the sample for next_time(). The azimuth rate tells which way a
  /// jump of nearly 180 deg between two samples went (near the zenith).
  void add(const LookAngles& look);

  std::size_t size() const { return count_; }
  std::int64_t start_ms() const { return start_ms_; }
  std::int64_t end_ms() const { return end_ms_; }
  std::int64_t step_ms() const { return step_ms_; }
  /// Unwrapped azimuth and elevation at `t_ms`, linearly interpolated; held
  /// at the ends outside the span.
  void at(std::int64_t t_ms, float& az_unwrapped_deg, float& el_deg) const;
  float az_first_deg() const { return az_[0]; }
  /// Sample `i` (0 <= i < size()).
  float az_sample(std::size_t i) const { return az_[i]; }
  float el_sample(std::size_t i) const { return el_[i]; }
  float az_lowest_deg() const { return az_lo_; }
  float az_highest_deg() const { return az_hi_; }
  float el_lowest_deg() const { return el_lo_; }
  float el_highest_deg() const { return el_hi_; }
  /// Replaces the samples by the path a rotator of these speeds can follow
  /// with the least largest error: the mean of a speed-limited follower run
  /// forward and one run backward in time (each obeys the limit, so their
  /// mean does). Where the target is slower than the rotator nothing
  /// changes; near the zenith the azimuth starts its swing early instead of
  /// trailing it, which halves the largest error. Call once, when complete.
  void limit_rates(float az_deg_s, float el_deg_s);
  /// Total azimuth and elevation travel along the pass.
  float az_path_deg() const { return az_path_; }
  float el_path_deg() const { return el_path_; }

 private:
  std::int64_t start_ms_ = 0, end_ms_ = 0, step_ms_ = kMinStepMs;
  std::size_t count_ = 0;
  float az_lo_ = 0, az_hi_ = 0, el_lo_ = 0, el_hi_ = 0, az_path_ = 0, el_path_ = 0;
  float az_[kCapacity] = {};
  float el_[kCapacity] = {};
  float scratch_[kCapacity] = {};
};

/// How a pass is laid onto the rotator: antenna az = unwrapped az + 180 (if
/// flipped) + az_offset_deg; antenna el = el, or 180 - el when flipped.
struct PassPlan {
  bool flip = false;
  float az_offset_deg = 0.0f;  ///< whole turns (plus nothing else): -720..720
  /// The pass fits the travel with this plan: no limit, no unwind. When
  /// false the plan either unwinds once (unwind_deg) or holds at the
  /// travel's end while the pass is beyond it (a 360 deg rotator without
  /// flip and a pass through its stop).
  bool fits = true;
  float preposition_deg = 0.0f;  ///< az + el degrees from where the antenna is to AOS
  float margin_deg = 0.0f;       ///< closest approach of the azimuth to a travel end
  /// A pass that fits no turn whole, split into two that do: from
  /// `unwind_at_ms` on, `unwind_deg` (+-360) is added to the azimuth. The
  /// split is where the unwind costs least: the lowest elevation the
  /// satellite reaches while the antenna turns round (`unwind_s`).
  float unwind_deg = 0.0f;
  std::int64_t unwind_at_ms = 0;
  float unwind_el_deg = 0.0f;  ///< the highest elevation during the unwind
  /// fits == false without an unwind: the follow phase holds the azimuth at
  /// the travel's end while the pass is beyond it, which costs this much
  /// (the squared pointing error over the pass, deg^2 s).
  float held_cost = 0.0f;
};

/// Chooses the wrap and the flip for the whole pass: among the plans that
/// keep it `margin_deg` inside the travel, the one that turns least to reach
/// AOS (the pass itself is the same length either way); a tie goes to no
/// flip, then to the plan farther from the ends.
/// When no plan fits, the one that loses least (the squared pointing error
/// over the pass): either it holds at the travel's end while the pass is
/// beyond it (the plan that starts inside and loses least so,
/// PassPlan::held_cost), or it unwinds once where the satellite is lowest
/// while the antenna turns round (PassPlan::unwind_deg; `unwind_s`: 360 deg
/// at the axis's speed, about 90 deg off on average; 0 = never).
PassPlan choose_plan(const PassTable& table, const Travel& travel, float az_now_deg,
                     float el_now_deg, float margin_deg, float unwind_s = 0.0f);

/// The antenna position the plan asks for at `t_ms`.
void plan_position(const PassTable& table, const PassPlan& plan, std::int64_t t_ms, float& az_deg,
                   float& el_deg);

}  // namespace rotord::tracking
