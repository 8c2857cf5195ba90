#pragma once
// Turning the beam to a place (issue 26): a Maidenhead locator or a
// latitude/longitude, short or long path, from the station (station.*
// settings). One implementation for the REST API, the console and MQTT, so
// each shows the same bearing and refuses for the same reason.
#include <cstddef>
#include <string_view>

#include "rotator/controller.hpp"
#include "tracking/places.hpp"

namespace rotord {

/// Where to turn: a place and which way round.
struct PlaceQuery {
  tracking::LatLon to;
  tracking::Path path = tracking::Path::kShort;
  char locator[11] = {};  ///< as given (upper-cased), empty for a lat/lon
};

/// Fills `q` from a locator (4-10 characters); nullptr, or why not.
const char* place_from_locator(std::string_view locator, PlaceQuery& q);
/// Fills `q` from a position; nullptr, or why not (out of range).
const char* place_from_lat_lon(double lat_deg, double lon_deg, PlaceQuery& q);
/// "short", "long", "sp" or "lp" (either case); nullptr, or why not.
const char* place_path(std::string_view word, PlaceQuery& q);
/// A line as the console and MQTT take it: "<locator> [short|long]" or
/// "<lat> <lon> [short|long]" (a comma may join lat and lon).
const char* parse_place(std::string_view line, PlaceQuery& q);

/// The bearing and distance to a place from the station, and whether the
/// rotator's travel reaches that bearing.
struct PlaceAim {
  tracking::Bearing bearing;
  bool reachable = false;
  /// Why not, naming the travel, when not reachable; else empty.
  char why[96] = {};
};
PlaceAim aim_at(Controller& c, const PlaceQuery& q);

/// Turns the beam to `aim` (refused when it is out of reach). An elevation
/// rotator that is flipped over the zenith (el > 90) keeps its elevation
/// but turns the azimuth so that the beam, not the mechanism, points there.
Error turn_to(Controller& c, const PlaceAim& aim);

/// The beam's direction from a mechanical position: an elevation past 90
/// points the beam back over the zenith (azimuth + 180, elevation 180 - el).
struct Beam {
  double az_deg = 0;  ///< 0..360
  double el_deg = 0;  ///< 0..90 (below 0 if the mechanism is below the horizon)
};
Beam beam_of(double az_mech_deg, double el_mech_deg, bool has_el);

/// Turns the beam to a compass heading (a preset), flip-aware as turn_to.
Error turn_beam_to(Controller& c, double az_deg);

}  // namespace rotord
