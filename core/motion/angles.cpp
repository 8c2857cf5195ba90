#include "motion/angles.hpp"

#include <cmath>

namespace rotord {

float wrap_360(float deg) {
  float w = std::fmod(deg, 360.0f);
  if (w < 0.0f) w += 360.0f;
  if (w >= 360.0f) w -= 360.0f;
  return w;
}

float wrap_180(float deg) {
  return wrap_360(deg + 180.0f) - 180.0f;
}

float unwrap_near(float deg, float near_deg) {
  return near_deg + wrap_180(deg - near_deg);
}

std::optional<float> choose_unwrapped_az(float az_deg, float current_deg, float min_deg,
                                         float max_deg, bool continuous) {
  if (continuous) return unwrap_near(az_deg, current_deg);
  const float base = wrap_360(az_deg);
  std::optional<float> best;
  // Travel is at most 720 deg, so candidates lie within [-720, 1080].
  for (int turn = -2; turn <= 3; ++turn) {
    const float candidate = base + 360.0f * static_cast<float>(turn);
    if (candidate < min_deg || candidate > max_deg) continue;
    if (!best || std::fabs(candidate - current_deg) < std::fabs(*best - current_deg))
      best = candidate;
  }
  return best;
}

}  // namespace rotord
