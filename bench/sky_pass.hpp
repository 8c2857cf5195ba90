#pragma once
// What the bench rows that follow the sky share (bench/tracking_mode.cpp,
// bench/client_passes.cpp): the ISS's elements of 2019-12-09, a UTC clock
// in step with virtual time, and the pointing error as issue 13 judges it.
#include <cmath>
#include <cstdint>
#include <optional>

#include "hal/wall_clock.hpp"
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

/// The great-circle angle (deg) between the antenna (its axes' angles,
/// flipped back when el > 90) and a sky direction; above 80 deg elevation
/// only the elevation counts (the azimuth is ill-conditioned there).
inline double pointing_error(double ant_az, double ant_el, double az, double el) {
  constexpr double kPi = 3.14159265358979323846;
  const auto rad = [](double d) { return d * kPi / 180.0; };
  if (ant_el > 90.0) {
    ant_az += 180.0;
    ant_el = 180.0 - ant_el;
  }
  if (el > 80.0) return std::fabs(ant_el - el);
  const double c = std::sin(rad(ant_el)) * std::sin(rad(el)) +
                   std::cos(rad(ant_el)) * std::cos(rad(el)) * std::cos(rad(ant_az - az));
  return std::acos(std::fmin(1.0, std::fmax(-1.0, c))) * 180.0 / kPi;
}

}  // namespace rotord::bench
