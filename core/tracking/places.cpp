#include "tracking/places.hpp"

#include <cmath>

namespace rotord::tracking {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kEarthMeanRadius_km = 6371.0088;

/// The index of `c` in a run of `count` letters from 'A' (either case), or -1.
int letter(char c, int count) {
  if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  const int i = c - 'A';
  return i >= 0 && i < count ? i : -1;
}

int digit(char c) {
  return c >= '0' && c <= '9' ? c - '0' : -1;
}

}  // namespace

bool maidenhead_centre(std::string_view loc, LatLon& out) {
  if (loc.size() < 4 || loc.size() > 10 || loc.size() % 2 != 0) return false;
  double lon = -180.0, lat = -90.0;
  double step_lon = 20.0, step_lat = 10.0;  // a field is 20 x 10 deg
  for (std::size_t pair = 0; pair * 2 < loc.size(); ++pair) {
    int x, y;
    if (pair == 0) {
      x = letter(loc[0], 18);
      y = letter(loc[1], 18);
    } else if (pair % 2 == 1) {
      step_lon /= 10.0;
      step_lat /= 10.0;
      x = digit(loc[pair * 2]);
      y = digit(loc[pair * 2 + 1]);
    } else {
      step_lon /= 24.0;
      step_lat /= 24.0;
      x = letter(loc[pair * 2], 24);
      y = letter(loc[pair * 2 + 1], 24);
    }
    if (x < 0 || y < 0) return false;
    lon += x * step_lon;
    lat += y * step_lat;
  }
  out.lat_deg = lat + step_lat / 2.0;
  out.lon_deg = lon + step_lon / 2.0;
  return true;
}

Bearing great_circle(const LatLon& from, const LatLon& to, Path path) {
  const double lat1 = from.lat_deg * kDeg, lat2 = to.lat_deg * kDeg;
  const double dlon = (to.lon_deg - from.lon_deg) * kDeg;
  // Haversine for the angle (well conditioned for short distances), atan2 for
  // the bearing.
  const double sin_dlat = std::sin((lat2 - lat1) / 2.0);
  const double sin_dlon = std::sin(dlon / 2.0);
  const double h = sin_dlat * sin_dlat + std::cos(lat1) * std::cos(lat2) * sin_dlon * sin_dlon;
  const double angle = 2.0 * std::atan2(std::sqrt(h), std::sqrt(1.0 - h));
  const double y = std::sin(dlon) * std::cos(lat2);
  const double x =
      std::cos(lat1) * std::sin(lat2) - std::sin(lat1) * std::cos(lat2) * std::cos(dlon);
  double az = std::atan2(y, x) / kDeg;
  Bearing b;
  b.distance_km = angle * kEarthMeanRadius_km;
  if (path == Path::kLong) {
    az += 180.0;
    b.distance_km = 2.0 * kPi * kEarthMeanRadius_km - b.distance_km;
  }
  az = std::fmod(az, 360.0);
  if (az < 0.0) az += 360.0;
  b.azimuth_deg = az;
  return b;
}

}  // namespace rotord::tracking
