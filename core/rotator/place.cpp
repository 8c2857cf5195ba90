#include "rotator/place.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord {
namespace {

/// A number word; false if it is not one.
bool number(std::string_view word, double& out) {
  char buf[24];
  if (word.empty() || word.size() >= sizeof buf) return false;
  std::memcpy(buf, word.data(), word.size());
  buf[word.size()] = '\0';
  char* end = nullptr;
  out = std::strtod(buf, &end);
  return end == buf + word.size() && std::isfinite(out);
}

double wrap360(double deg) {
  deg = std::fmod(deg, 360.0);
  return deg < 0.0 ? deg + 360.0 : deg;
}

bool flipped(const Controller& c) {
  const RotatorStatus s = c.status();
  return s.el.present && s.el.position_valid && s.el.position_deg > 90.0f;
}

}  // namespace

const char* place_from_locator(std::string_view locator, PlaceQuery& q) {
  if (locator.size() < 4 || locator.size() > 10 || locator.size() % 2 != 0)
    return "a locator has 4, 6, 8 or 10 characters (e.g. JO62QM)";
  if (!tracking::maidenhead_centre(locator, q.to))
    return "not a Maidenhead locator: field A-R, square 0-9, subsquare A-X, then 0-9, A-X";
  for (std::size_t n = 0; n < locator.size(); ++n) {
    const char c = locator[n];
    q.locator[n] = c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c;
  }
  q.locator[locator.size()] = '\0';
  return nullptr;
}

const char* place_from_lat_lon(double lat_deg, double lon_deg, PlaceQuery& q) {
  if (!std::isfinite(lat_deg) || lat_deg < -90.0 || lat_deg > 90.0)
    return "latitude is outside -90..90";
  if (!std::isfinite(lon_deg) || lon_deg < -180.0 || lon_deg > 180.0)
    return "longitude is outside -180..180";
  q.to = {lat_deg, lon_deg};
  q.locator[0] = '\0';
  return nullptr;
}

const char* place_path(std::string_view word, PlaceQuery& q) {
  if (text::iequals(word, "short") || text::iequals(word, "sp")) {
    q.path = tracking::Path::kShort;
  } else if (text::iequals(word, "long") || text::iequals(word, "lp")) {
    q.path = tracking::Path::kLong;
  } else {
    return "the path is short or long";
  }
  return nullptr;
}

const char* parse_place(std::string_view line, PlaceQuery& q) {
  std::string_view words[4];
  std::size_t count = 0;
  std::string_view rest = line;
  while (count < 4) {
    // A comma joins lat and lon: "52.5,13.4" is two words.
    while (!rest.empty() && (rest.front() == ' ' || rest.front() == ',')) rest.remove_prefix(1);
    if (rest.empty()) break;
    std::size_t end = 0;
    while (end < rest.size() && rest[end] != ' ' && rest[end] != ',') ++end;
    words[count++] = text::slice(rest, 0, end);
    rest.remove_prefix(end);
  }
  while (!rest.empty() && (rest.front() == ' ' || rest.front() == ',')) rest.remove_prefix(1);
  if (count == 0 || !rest.empty())
    return "give a locator or a latitude and longitude, then short or long";
  double lat = 0, lon = 0;
  std::size_t used = 1;
  const char* why = nullptr;
  if (count >= 2 && number(words[0], lat)) {
    if (!number(words[1], lon)) return "a position is <lat> <lon> in degrees";
    why = place_from_lat_lon(lat, lon, q);
    used = 2;
  } else {
    why = place_from_locator(words[0], q);
  }
  if (why != nullptr) return why;
  q.path = tracking::Path::kShort;
  if (count == used) return nullptr;
  if (count > used + 1) return "too many words: <place> [short|long]";
  return place_path(words[used], q);
}

PlaceAim aim_at(Controller& c, const PlaceQuery& q) {
  PlaceAim aim;
  const settings::Settings& s = c.settings();
  const tracking::LatLon station{s.get(settings::Id::kStationLatDeg),
                                 s.get(settings::Id::kStationLonDeg)};
  aim.bearing = tracking::great_circle(station, q.to, q.path);
  const double mech =
      flipped(c) ? wrap360(aim.bearing.azimuth_deg + 180.0) : aim.bearing.azimuth_deg;
  aim.reachable = c.resolve_az(static_cast<float>(mech), AzTarget::kCompass).has_value();
  if (!aim.reachable) {
    const Limits l = c.limits();
    std::snprintf(aim.why, sizeof aim.why, "bearing %.1f is outside the travel %g..%g",
                  aim.bearing.azimuth_deg, static_cast<double>(l.az_min_deg),
                  static_cast<double>(l.az_max_deg));
  }
  return aim;
}

Error turn_beam_to(Controller& c, double az_deg) {
  const double mech = flipped(c) ? wrap360(az_deg + 180.0) : wrap360(az_deg);
  return c.go_to(static_cast<float>(mech), std::nullopt, AzTarget::kCompass);
}

Error turn_to(Controller& c, const PlaceAim& aim) {
  if (!aim.reachable) return Error::kOutOfRange;
  return turn_beam_to(c, aim.bearing.azimuth_deg);
}

Beam beam_of(double az_mech_deg, double el_mech_deg, bool has_el) {
  Beam b;
  if (has_el && el_mech_deg > 90.0) {
    b.az_deg = wrap360(az_mech_deg + 180.0);
    b.el_deg = 180.0 - el_mech_deg;
  } else {
    b.az_deg = wrap360(az_mech_deg);
    b.el_deg = has_el ? el_mech_deg : 0.0;
  }
  return b;
}

}  // namespace rotord
