#pragma once
#include <cstddef>
#include <optional>
#include <string_view>

namespace rotord::protocol::rotctld {

// The pure helpers rotctl offers next to the rotator commands (L l D d E e B
// A a), with the conventions of Hamlib's locator functions so replies match
// rotctld's: Maidenhead pairs of 18/10/24/10/24/10 fields, a sphere of
// 111.2 km per degree of arc, QRB azimuths rounded to whole degrees.

struct LonLat {
  double lon_deg;
  double lat_deg;
};

/// Longitude/latitude to a locator of `pairs` pairs (1..6), e.g. "JO11AA";
/// false when `pairs` is out of range. `out` needs 2 * pairs + 1 bytes.
bool lonlat_to_locator(double lon_deg, double lat_deg, int pairs, char* out, std::size_t capacity);
/// The centre of a locator's square (letters in either case; extra pairs
/// beyond six are ignored); nullopt for a malformed locator.
std::optional<LonLat> locator_to_lonlat(std::string_view locator);

struct Dms {
  int degrees;
  int minutes;
  double seconds;
  int south_west;  ///< 1 when the value is negative
};
/// Degrees, minutes, seconds (magnitudes) and a sign flag to decimal degrees.
double dms_to_decimal(int degrees, int minutes, double seconds, int south_west);
double dmmm_to_decimal(int degrees, double minutes, int south_west);
/// Decimal degrees folded into -180..180 to degrees, minutes, seconds.
Dms decimal_to_dms(double decimal_deg);

struct Qrb {
  double distance_km;
  double azimuth_deg;  ///< rounded to whole degrees
};
/// Great-circle distance and bearing; nullopt outside +-180 / +-90.
std::optional<Qrb> qrb(double lon1_deg, double lat1_deg, double lon2_deg, double lat2_deg);
double long_path_km(double short_path_km);
/// The opposite bearing; nullopt outside 0..360.
std::optional<double> long_path_azimuth(double short_path_deg);

}  // namespace rotord::protocol::rotctld
