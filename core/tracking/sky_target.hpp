#pragma once
#include <cstdint>

#include "tracking/observer.hpp"
#include "tracking/sgp4.hpp"
#include "tracking/sun_moon.hpp"
#include "tracking/tle.hpp"

namespace rotord::tracking {

enum class TargetKind : std::uint8_t { kNone, kSatellite, kSun, kMoon };

/// Something in the sky to point at: a satellite from its TLE, the Sun or the
/// Moon. One value type (no heap, no virtual calls), about 1.2 KB.
class SkyTarget {
 public:
  /// A satellite. Fails (and leaves the target empty) when SGP4 refuses the
  /// elements at their epoch.
  Sgp4Error set_satellite(const Tle& tle);
  void set_body(Body body);

  TargetKind kind() const { return kind_; }
  /// The satellite's elements (meaningful for kSatellite only).
  const Tle& tle() const { return tle_; }

  /// Where the target is at `unix_ms` (UTC) from `observer`. For satellites,
  /// SGP4's error when the propagation fails there (e.g. decayed by then).
  Sgp4Error look(std::int64_t unix_ms, const Observer& observer, LookAngles& out);

 private:
  TargetKind kind_ = TargetKind::kNone;
  Tle tle_;
  Sgp4 sgp4_;
};

}  // namespace rotord::tracking
