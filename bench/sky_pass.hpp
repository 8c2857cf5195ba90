#pragma once
// What the bench rows that follow the sky share (bench/tracking_mode.cpp,
// bench/client_passes.cpp): the ISS's elements of 2019-12-09, a UTC clock
// in step with virtual time, and the pointing error (the sky angle).
#include <cmath>
#include <cstdint>
#include <optional>

#include "hal/wall_clock.hpp"
#include "sky_angle.hpp"
#include "util/time.hpp"

namespace rotord::bench {

inline constexpr const char* kIss1 =
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991";
inline constexpr const char* kIss2 =
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482";

/// UTC = `start` + the controller's virtual time.
class VirtualUtc final : public hal::WallClock {
 public:
  VirtualUtc(std::int64_t start, const Millis* now) : start_(start), now_(now) {}
  std::optional<std::int64_t> unix_ms() const override { return start_ + *now_; }

 private:
  std::int64_t start_;
  const Millis* now_;
};

/// The pointing error: the angle on the sky between the antenna (its
/// axes' angles, over the top when el > 90) and a sky direction. Near the
/// zenith too: there the azimuth is ill-conditioned as an axis figure, but
/// the sky angle already weighs it by how far it moves the beam.
inline double pointing_error(double ant_az, double ant_el, double az, double el) {
  return sky_angle_deg(ant_az, ant_el, az, el);
}

}  // namespace rotord::bench
