#include "protocol/gs232_angles.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord::protocol::gs232 {

AzRange az_range(const settings::Settings& settings, const Limits& limits) {
  switch (settings.i(settings::Id::kGs232AzRange)) {
    case 1:
      return AzRange::k360;
    case 2:
      return AzRange::k450;
    default:
      return !limits.az_continuous && limits.az_max_deg > 360.0f ? AzRange::k450 : AzRange::k360;
  }
}

namespace {

/// Rounds to whole degrees without overflow (a broken sensor must not make the
/// reply formatting undefined).
long whole_degrees(float deg) {
  if (!std::isfinite(deg)) return 0;
  if (deg > 100000.0f) deg = 100000.0f;
  if (deg < -100000.0f) deg = -100000.0f;
  return std::lround(deg);
}

}  // namespace

int report_az_deg(float unwrapped_deg, AzRange range, bool continuous) {
  const long deg = whole_degrees(unwrapped_deg);
  if (!continuous && deg >= 0 && deg <= full_scale_deg(range)) return static_cast<int>(deg);
  long bearing = deg % 360;
  if (bearing < 0) bearing += 360;
  return static_cast<int>(bearing);
}

int report_el_deg(float el_deg) {
  const long deg = whole_degrees(el_deg);
  if (deg < 0) return 0;
  if (deg > 180) return 180;
  return static_cast<int>(deg);
}

AzGoal az_goal(int gs232_deg, const Limits& limits) {
  const auto deg = static_cast<float>(gs232_deg);
  if (!limits.az_continuous && deg >= limits.az_min_deg && deg <= limits.az_max_deg)
    return {deg, AzTarget::kUnwrapped};
  return {wrap_360(deg), AzTarget::kCompass};
}

}  // namespace rotord::protocol::gs232
