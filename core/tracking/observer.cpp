#include "tracking/observer.hpp"

#include <cmath>

namespace rotord::tracking {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRad2Deg = 180.0 / kPi;
constexpr double kWgs84A_km = 6378.137;
constexpr double kWgs84F = 1.0 / 298.257223563;

}  // namespace

EcefState teme_to_ecef(const TemeState& teme, double gmst_rad) {
  const double c = std::cos(gmst_rad);
  const double s = std::sin(gmst_rad);
  EcefState e;
  e.r_km[0] = c * teme.r_km[0] + s * teme.r_km[1];
  e.r_km[1] = -s * teme.r_km[0] + c * teme.r_km[1];
  e.r_km[2] = teme.r_km[2];
  e.v_km_s[0] = c * teme.v_km_s[0] + s * teme.v_km_s[1] + kEarthRotationRad_s * e.r_km[1];
  e.v_km_s[1] = -s * teme.v_km_s[0] + c * teme.v_km_s[1] - kEarthRotationRad_s * e.r_km[0];
  e.v_km_s[2] = teme.v_km_s[2];
  return e;
}

void geodetic_to_ecef(const Geodetic& where, double r_km[3]) {
  const double lat = where.lat_deg / kRad2Deg;
  const double lon = where.lon_deg / kRad2Deg;
  const double e2 = kWgs84F * (2.0 - kWgs84F);
  const double sin_lat = std::sin(lat);
  const double n = kWgs84A_km / std::sqrt(1.0 - e2 * sin_lat * sin_lat);
  const double h_km = where.alt_m / 1000.0;
  r_km[0] = (n + h_km) * std::cos(lat) * std::cos(lon);
  r_km[1] = (n + h_km) * std::cos(lat) * std::sin(lon);
  r_km[2] = (n * (1.0 - e2) + h_km) * sin_lat;
}

Observer::Observer(const Geodetic& where) : where_(where) {
  sin_lat_ = std::sin(where.lat_deg / kRad2Deg);
  cos_lat_ = std::cos(where.lat_deg / kRad2Deg);
  sin_lon_ = std::sin(where.lon_deg / kRad2Deg);
  cos_lon_ = std::cos(where.lon_deg / kRad2Deg);
  geodetic_to_ecef(where, r_km_);
}

LookAngles Observer::look(const EcefState& target) const {
  double rho[3], rho_dot[3];
  for (int i = 0; i < 3; ++i) {
    rho[i] = target.r_km[i] - r_km_[i];
    rho_dot[i] = target.v_km_s[i];  // the observer is fixed in this frame
  }
  // East, north, up (the normal of the ellipsoid at the observer).
  auto enu = [&](const double* v, double& e, double& n, double& u) {
    e = -sin_lon_ * v[0] + cos_lon_ * v[1];
    n = -sin_lat_ * cos_lon_ * v[0] - sin_lat_ * sin_lon_ * v[1] + cos_lat_ * v[2];
    u = cos_lat_ * cos_lon_ * v[0] + cos_lat_ * sin_lon_ * v[1] + sin_lat_ * v[2];
  };
  double e, n, u, de, dn, du;
  enu(rho, e, n, u);
  enu(rho_dot, de, dn, du);
  const double h2 = e * e + n * n;
  const double h = std::sqrt(h2);
  const double range = std::sqrt(h2 + u * u);
  LookAngles look;
  look.range_km = range;
  look.el_deg = std::atan2(u, h) * kRad2Deg;
  double az = std::atan2(e, n) * kRad2Deg;
  if (az < 0.0) az += 360.0;
  look.az_deg = az;
  look.range_rate_km_s = range > 0.0 ? (e * de + n * dn + u * du) / range : 0.0;
  if (h2 > 0.0) {
    look.az_rate_deg_s = (n * de - e * dn) / h2 * kRad2Deg;
    const double h_dot = (e * de + n * dn) / h;
    look.el_rate_deg_s = (du * h - u * h_dot) / (range * range) * kRad2Deg;
  }
  return look;
}

}  // namespace rotord::tracking
