#pragma once
#include <optional>

namespace rotord {

/// Maps any angle into [0, 360).
float wrap_360(float deg);
/// Maps any angle into [-180, 180).
float wrap_180(float deg);

/// The unwrapped angle congruent to `deg` (mod 360) that is nearest to `near_deg`.
float unwrap_near(float deg, float near_deg);

/// Chooses where a compass azimuth (0..360) is reached on a rotator whose
/// unwrapped travel is [min_deg, max_deg]: among the congruent angles inside
/// the travel, the one that turns least from `current_deg`. Continuous
/// rotators take the shortest way. Empty when no congruent angle is reachable.
std::optional<float> choose_unwrapped_az(float az_deg, float current_deg, float min_deg,
                                         float max_deg, bool continuous);

}  // namespace rotord
