#pragma once
#include <string_view>

namespace rotord::tracking {

/// A point on the Earth by latitude and longitude (degrees, north and east positive).
struct LatLon {
  double lat_deg = 0;
  double lon_deg = 0;
};

/// The centre of a Maidenhead locator of 4, 6, 8 or 10 characters (field
/// A-R, square 0-9, subsquare a-x, extended square 0-9, its subsquare a-x;
/// letters in either case). False for anything else.
bool maidenhead_centre(std::string_view locator, LatLon& out);

enum class Path { kShort, kLong };

struct Bearing {
  double azimuth_deg = 0;  ///< initial great-circle bearing, 0..360 from north
  double distance_km = 0;  ///< along that great circle
};

/// The great-circle bearing and distance from `from` to `to` on a sphere of
/// the Earth's mean radius (6371.0088 km; the ellipsoid changes bearings by
/// up to about 0.2 deg, far less than an antenna's beam). The long path leaves
/// in the opposite direction and goes the rest of the way round.
Bearing great_circle(const LatLon& from, const LatLon& to, Path path = Path::kShort);

}  // namespace rotord::tracking
