#include "tracking/sky_target.hpp"

#include "tracking/julian.hpp"

namespace rotord::tracking {

Sgp4Error SkyTarget::set_satellite(const Tle& tle) {
  kind_ = TargetKind::kNone;
  const Sgp4Error error = sgp4_.init(tle);
  if (error != Sgp4Error::kOk) return error;
  tle_ = tle;
  kind_ = TargetKind::kSatellite;
  return Sgp4Error::kOk;
}

void SkyTarget::set_body(Body body) {
  kind_ = body == Body::kSun ? TargetKind::kSun : TargetKind::kMoon;
}

Sgp4Error SkyTarget::look(std::int64_t unix_ms, const Observer& observer, LookAngles& out) {
  switch (kind_) {
    case TargetKind::kSun:
    case TargetKind::kMoon:
      out = observer.look(body_ecef(kind_ == TargetKind::kSun ? Body::kSun : Body::kMoon, unix_ms));
      return Sgp4Error::kOk;
    case TargetKind::kSatellite: {
      const double tsince_min = (static_cast<double>(unix_ms) - sgp4_.epoch_unix_ms()) / 60000.0;
      TemeState teme;
      const Sgp4Error error = sgp4_.propagate(tsince_min, teme);
      if (error != Sgp4Error::kOk) return error;
      out = observer.look(teme_to_ecef(teme, gmst_rad(days_since_j2000(unix_ms))));
      return Sgp4Error::kOk;
    }
    case TargetKind::kNone:
      break;
  }
  out = LookAngles{};
  return Sgp4Error::kNoTarget;
}

}  // namespace rotord::tracking
