#pragma once
#include "tracking/sgp4.hpp"

namespace rotord::tracking {

/// A place on the WGS-84 ellipsoid: geodetic latitude and longitude (east
/// positive), height above the ellipsoid.
struct Geodetic {
  double lat_deg = 0;
  double lon_deg = 0;
  double alt_m = 0;
};

/// A position and velocity in an Earth-fixed frame (ECEF; here the pseudo
/// Earth-fixed frame of TEME rotated by GMST, polar motion neglected).
struct EcefState {
  double r_km[3] = {};
  double v_km_s[3] = {};
};

/// Where a target is seen from an observer: azimuth from north through east,
/// elevation above the ellipsoid's horizon (geometric, no refraction), slant
/// range, and their rates.
struct LookAngles {
  double az_deg = 0;  ///< 0..360
  double el_deg = 0;
  double range_km = 0;
  double range_rate_km_s = 0;  ///< positive when receding (Sun/Moon: no radial part)
  double az_rate_deg_s = 0;
  double el_rate_deg_s = 0;
};

/// Earth's rotation rate, rad/s (Vallado's value, length of day not modelled).
inline constexpr double kEarthRotationRad_s = 7.292115146706979e-5;

/// TEME to the pseudo Earth-fixed frame through GMST (IAU-82) with UT1 = UTC
/// and no polar motion, as in Vallado et al. 2006 (teme2ecef without xp, yp):
/// the velocity loses the Earth's rotation (v - omega x r).
EcefState teme_to_ecef(const TemeState& teme, double gmst_rad);

/// An observer on the WGS-84 ellipsoid, its trigonometry computed once.
class Observer {
 public:
  Observer() : Observer(Geodetic{}) {}
  explicit Observer(const Geodetic& where);

  const Geodetic& where() const { return where_; }
  /// The observer's own Earth-fixed position, km.
  const double* r_km() const { return r_km_; }

  /// Look angles of an Earth-fixed target.
  LookAngles look(const EcefState& target) const;

 private:
  Geodetic where_;
  double sin_lat_ = 0, cos_lat_ = 1, sin_lon_ = 0, cos_lon_ = 1;
  double r_km_[3] = {};
};

/// Geodetic to Earth-fixed (WGS-84: a = 6378.137 km, f = 1/298.257223563).
void geodetic_to_ecef(const Geodetic& where, double r_km[3]);

}  // namespace rotord::tracking
