#include "protocol/rotctld_locator.hpp"

#include <cmath>
#include <numbers>

namespace rotord::protocol::rotctld {
namespace {

constexpr int kFieldCounts[] = {18, 10, 24, 10, 24, 10};  // letters, digits, letters...
constexpr int kMaxPairs = 6;
constexpr double kKmPerDegree = 111.2;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace

bool lonlat_to_locator(double lon_deg, double lat_deg, int pairs, char* out, std::size_t capacity) {
  if (pairs < 1 || pairs > kMaxPairs || capacity < static_cast<std::size_t>(2 * pairs + 1))
    return false;
  // Longitude counts in half degrees so both axes span 180; both start at
  // the antimeridian / south pole. The 1e-6 keeps exact borders in the
  // upper square despite rounding.
  const double start[2] = {lon_deg / 2.0, lat_deg};
  for (int axis = 0; axis < 2; ++axis) {
    double rest = std::fmod(start[axis] + 270.000001, 180.0);
    int divisions = 1;
    for (int p = 0; p < pairs; ++p) {
      divisions *= kFieldCounts[p];
      const double size = 180.0 / divisions;
      const int index = static_cast<int>(rest / size);
      rest -= size * index;
      out[2 * p + axis] = static_cast<char>((kFieldCounts[p] == 10 ? '0' : 'A') + index);
    }
  }
  out[2 * pairs] = '\0';
  return true;
}

std::optional<LonLat> locator_to_lonlat(std::string_view locator) {
  int pairs = static_cast<int>(locator.size() / 2);
  if (pairs > kMaxPairs) pairs = kMaxPairs;
  if (pairs < 1) return std::nullopt;
  double result[2] = {};
  for (int axis = 0; axis < 2; ++axis) {
    double value = -90.0;
    int divisions = 1;
    for (int p = 0; p < pairs; ++p) {
      const char c = locator[static_cast<std::size_t>(2 * p + axis)];
      int index = -1;
      if (kFieldCounts[p] == 10) {
        index = c - '0';
      } else if (c >= 'A' && c <= 'Z') {
        index = c - 'A';
      } else if (c >= 'a' && c <= 'z') {
        index = c - 'a';
      }
      if (index < 0 || index >= kFieldCounts[p]) return std::nullopt;
      divisions *= kFieldCounts[p];
      value += index * 180.0 / divisions;
    }
    result[axis] = value + 90.0 / divisions;  // the centre of the smallest square
  }
  return LonLat{result[0] * 2.0, result[1]};
}

double dms_to_decimal(int degrees, int minutes, double seconds, int south_west) {
  const double d = std::abs(degrees) + std::abs(minutes) / 60.0 + std::fabs(seconds) / 3600.0;
  return south_west == 1 ? -d : d;
}

double dmmm_to_decimal(int degrees, double minutes, int south_west) {
  const double d = std::abs(degrees) + std::fabs(minutes) / 60.0;
  return south_west == 1 ? -d : d;
}

Dms decimal_to_dms(double decimal_deg) {
  // Fold into -180..180 (270 is -90, -270 is 90); 180 stays positive.
  const double folded = decimal_deg >= 0.0 ? std::fmod(decimal_deg + 180.0, 360.0) - 180.0
                                           : std::fmod(decimal_deg - 180.0, 360.0) + 180.0;
  Dms r{};
  r.south_west = folded < 0.0 && folded != -180.0 ? 1 : 0;
  double rest = std::fabs(folded);
  r.degrees = static_cast<int>(std::floor(rest));
  rest = 60.0 * (rest - r.degrees);
  r.minutes = static_cast<int>(std::floor(rest));
  r.seconds = 60.0 * (rest - r.minutes);
  return r;
}

std::optional<Qrb> qrb(double lon1_deg, double lat1_deg, double lon2_deg, double lat2_deg) {
  if (std::fabs(lat1_deg) > 90.0 || std::fabs(lat2_deg) > 90.0 || std::fabs(lon1_deg) > 180.0 ||
      std::fabs(lon2_deg) > 180.0 || std::isnan(lat1_deg + lat2_deg + lon1_deg + lon2_deg))
    return std::nullopt;
  // Just off the poles, so acos stays in its domain.
  auto off_pole = [](double lat) {
    return lat == 90.0 ? 89.999999999 : lat == -90.0 ? -89.999999999 : lat;
  };
  const double lat1 = off_pole(lat1_deg) / kDegPerRad;
  const double lat2 = off_pole(lat2_deg) / kDegPerRad;
  const double dlon = (lon2_deg - lon1_deg) / kDegPerRad;
  const double cos_arc =
      std::sin(lat1) * std::sin(lat2) + std::cos(lat1) * std::cos(lat2) * std::cos(dlon);
  if (cos_arc > 0.999999999999999) return Qrb{0.0, 0.0};           // the same place
  if (cos_arc < -0.999999) return Qrb{180.0 * kKmPerDegree, 0.0};  // antipodes: any bearing
  const double distance_km = kKmPerDegree * kDegPerRad * std::acos(cos_arc);
  double az = kDegPerRad * std::atan2(std::sin(dlon) * std::cos(lat2),
                                      std::cos(lat1) * std::sin(lat2) -
                                          std::sin(lat1) * std::cos(lat2) * std::cos(dlon));
  az = std::fmod(360.0 + az, 360.0);
  if (az < 0.0) az += 360.0;
  if (az >= 360.0) az -= 360.0;
  return Qrb{distance_km, std::floor(az + 0.5)};
}

double long_path_km(double short_path_km) {
  return kKmPerDegree * 360.0 - short_path_km;
}

std::optional<double> long_path_azimuth(double short_path_deg) {
  if (short_path_deg == 0.0 || short_path_deg == 360.0) return 180.0;
  if (short_path_deg == 180.0) return 0.0;
  if (short_path_deg > 0.0 && short_path_deg < 180.0) return 180.0 + short_path_deg;
  if (short_path_deg > 180.0 && short_path_deg < 360.0) return short_path_deg - 180.0;
  return std::nullopt;
}

}  // namespace rotord::protocol::rotctld
