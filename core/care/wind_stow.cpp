#include "care/wind_stow.hpp"

#include <cmath>

#include "util/text.hpp"

namespace rotord::care {

const char* wind_state_name(WindState s) {
  switch (s) {
    case WindState::kOff:
      return "off";
    case WindState::kCalm:
      return "calm";
    case WindState::kRising:
      return "rising";
    case WindState::kStowed:
      return "stowed";
    case WindState::kOverride:
      return "override";
  }
  return "?";
}

const char* wind_reject_name(WindReject r) {
  switch (r) {
    case WindReject::kGarbage:
      return "garbage";
    case WindReject::kNegative:
      return "negative";
    case WindReject::kTooHigh:
      return "too_high";
    case WindReject::kBadDirection:
      return "bad_direction";
    case WindReject::kStale:
      return "stale";
  }
  return "?";
}

void WindStow::configure(const WindConfig& config) {
  const bool source_changed = config.source != config_.source;
  config_ = config;
  if (!source_changed) return;
  // Another source: what the old one said no longer counts.
  have_speed_ = false;
  have_dir_ = false;
  above_since_ms_ = -1;
  calm_since_ms_ = -1;
  stopped_ = false;
  state_ = config_.source == WindSource::kOff ? WindState::kOff : WindState::kCalm;
}

void WindStow::speed(float mps, Millis now) {
  if (!std::isfinite(mps)) return reject(WindReject::kGarbage);
  if (mps < 0.0f) return reject(WindReject::kNegative);
  if (mps > kMaxSpeedMps) return reject(WindReject::kTooHigh);
  ++readings_;
  have_speed_ = true;
  stale_counted_ = false;
  speed_mps_ = mps;
  speed_at_ms_ = now;
  // Spells: the first reading of a run at or above the threshold, and of a
  // run below the calm speed. Any reading outside a run ends it.
  if (mps >= config_.stow_mps) {
    if (above_since_ms_ < 0) above_since_ms_ = now;
  } else {
    above_since_ms_ = -1;
  }
  if (mps < config_.calm_mps) {
    if (calm_since_ms_ < 0) calm_since_ms_ = now;
  } else {
    calm_since_ms_ = -1;
  }
}

void WindStow::direction(float deg, Millis now) {
  if (!std::isfinite(deg) || deg < 0.0f || deg > 360.0f) return reject(WindReject::kBadDirection);
  have_dir_ = true;
  dir_deg_ = deg >= 360.0f ? 0.0f : deg;
  dir_at_ms_ = now;
}

void WindStow::speed_text(std::string_view text, float to_mps, Millis now) {
  double value = 0.0;
  if (!text::parse_double(text::trim(text), value)) return reject(WindReject::kGarbage);
  speed(static_cast<float>(value) * to_mps, now);
}

void WindStow::direction_text(std::string_view text, Millis now) {
  double value = 0.0;
  if (!text::parse_double(text::trim(text), value)) return reject(WindReject::kBadDirection);
  direction(static_cast<float>(value), now);
}

void WindStow::enter_stowed(Millis now) {
  state_ = WindState::kStowed;
  stowed_at_ms_ = now;
  stow_requested_ = true;
  stopped_ = false;
  ++stows_;
}

void WindStow::tick(Millis now) {
  now_ = now;
  if (config_.source == WindSource::kOff) {
    state_ = WindState::kOff;
    return;
  }
  if (have_speed_ && !fresh(now) && !stale_counted_) {
    // A silent source is counted once a silence, and its old value forgotten
    // for stowing: an hour-old gust must not stow the antenna now.
    reject(WindReject::kStale);
    stale_counted_ = true;
    above_since_ms_ = -1;
    calm_since_ms_ = -1;
  }
  const bool calm_long_enough =
      fresh(now) && calm_since_ms_ >= 0 && now - calm_since_ms_ >= config_.calm_ms;
  switch (state_) {
    case WindState::kOff:
    case WindState::kCalm:
    case WindState::kRising:
      if (fresh(now) && above_since_ms_ >= 0) {
        if (now - above_since_ms_ >= config_.hold_ms) {
          enter_stowed(now);
        } else {
          state_ = WindState::kRising;
        }
      } else {
        state_ = WindState::kCalm;
      }
      break;
    case WindState::kStowed:
      if (calm_long_enough) {
        state_ = WindState::kCalm;
        stopped_ = false;
      }
      break;
    case WindState::kOverride:
      if (calm_long_enough) {
        state_ = WindState::kCalm;
      } else if (now >= override_until_ms_) {
        enter_stowed(now);  // still windy: stowed again
      }
      break;
  }
  if (state_ == WindState::kStowed && config_.into_wind && !stopped_ && aimed_ &&
      has_fresh_direction(now)) {
    // The wind veered: the boom follows it, but not every degree of it.
    float diff = std::fabs(dir_deg_ - aimed_dir_deg_);
    if (diff > 180.0f) diff = 360.0f - diff;
    if (diff > kReaimDeg) stow_requested_ = true;
  }
}

bool WindStow::override_now(Millis now, Millis for_ms) {
  if (state_ != WindState::kStowed && state_ != WindState::kOverride) return false;
  override_until_ms_ = now + (for_ms > 0 ? for_ms : config_.override_ms);
  state_ = WindState::kOverride;
  stow_requested_ = false;
  ++overrides_;
  return true;
}

void WindStow::end_override() {
  if (state_ == WindState::kOverride) enter_stowed(now_);
}

Millis WindStow::override_left_ms(Millis now) const {
  if (state_ != WindState::kOverride || override_until_ms_ <= now) return 0;
  return override_until_ms_ - now;
}

Millis WindStow::calm_left_ms(Millis now) const {
  if (state_ != WindState::kStowed && state_ != WindState::kOverride) return 0;
  if (!fresh(now) || calm_since_ms_ < 0) return config_.calm_ms;
  const Millis left = config_.calm_ms - (now - calm_since_ms_);
  return left > 0 ? left : 0;
}

}  // namespace rotord::care
