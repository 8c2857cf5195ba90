// The rules checked when a value is saved (Settings::check_dependent): values
// that depend on each other, so that a save cannot leave a setting that
// cannot work (issue 23: park.az_deg 500 on a 0..450 rotator was saved, and
// PARK then failed). Each message names both settings and their values.
#include <cstdio>
#include <initializer_list>

#include "settings/settings.hpp"

namespace rotord::settings {

namespace {

/// One axis's travel as the messages name it.
struct Travel {
  const char* prefix;  ///< "az"
  const char* word;    ///< "azimuth"
  double min_deg;
  double max_deg;
};

/// A position a command goes to (park, wind stow) must lie within the
/// travel: the same message for each, naming both settings and values.
bool outside_travel(char* out, std::size_t cap, const char* key, double deg, const Travel& t,
                    const char* who) {
  if (!(deg < t.min_deg || deg > t.max_deg)) return false;  // a NaN is no finding
  std::snprintf(out, cap,
                "%s %g is outside the %s travel %s.min_deg..%s.max_deg (%g..%g): %s could not "
                "go there",
                key, deg, t.word, t.prefix, t.prefix, t.min_deg, t.max_deg, who);
  return true;
}

/// A slow zone as long as the travel makes every move a slow one.
bool slow_zone_too_long(char* out, std::size_t cap, double zone_deg, double travel_deg,
                        const Travel& t) {
  if (!(zone_deg >= travel_deg)) return false;
  std::snprintf(out, cap,
                "%s.slow_zone_deg %g must be shorter than the %s travel %s.min_deg..%s.max_deg "
                "(%g deg)",
                t.prefix, zone_deg, t.word, t.prefix, t.prefix, travel_deg);
  return true;
}

}  // namespace

template <typename Touched>
Rejection Settings::check_dependent_rules(Touched touched) const {
  const bool continuous = b(Id::kAzContinuous);
  const bool el_on = b(Id::kElEnabled);
  const Travel az{"az", "azimuth", get(Id::kAzMinDeg), get(Id::kAzMaxDeg)};
  const Travel el{"el", "elevation", get(Id::kElMinDeg), get(Id::kElMaxDeg)};
  const Rejection out_of_range{Error::kOutOfRange, detail_};
  // A continuous azimuth takes any bearing: the park azimuth wraps.
  if (!continuous && touched({Id::kParkAzDeg, Id::kAzMinDeg, Id::kAzMaxDeg, Id::kAzContinuous}) &&
      outside_travel(detail_, sizeof detail_, "park.az_deg", get(Id::kParkAzDeg), az, "PARK"))
    return out_of_range;
  if (el_on && touched({Id::kParkElDeg, Id::kElMinDeg, Id::kElMaxDeg, Id::kElEnabled}) &&
      outside_travel(detail_, sizeof detail_, "park.el_deg", get(Id::kParkElDeg), el, "PARK"))
    return out_of_range;
  // Wind stow (docs/care.md): checked once a source is set, so an unused
  // default never blocks a change of the travel.
  const bool wind_on = i(Id::kWindSource) != 0;
  if (wind_on && !continuous &&
      touched(
          {Id::kWindStowAzDeg, Id::kWindSource, Id::kAzMinDeg, Id::kAzMaxDeg, Id::kAzContinuous}) &&
      outside_travel(detail_, sizeof detail_, "wind.stow_az_deg", get(Id::kWindStowAzDeg), az,
                     "a wind stow"))
    return out_of_range;
  if (wind_on && touched({Id::kWindCalmMps, Id::kWindStowMps, Id::kWindSource}) &&
      get(Id::kWindCalmMps) > get(Id::kWindStowMps)) {
    std::snprintf(detail_, sizeof detail_,
                  "wind.calm_mps %g is above wind.stow_mps %g: the wind could be calm and a "
                  "storm at once",
                  get(Id::kWindCalmMps), get(Id::kWindStowMps));
    return out_of_range;
  }
  const double az_travel_deg = continuous ? 360.0 : az.max_deg - az.min_deg;
  if (touched({Id::kAzSlowZoneDeg, Id::kAzMinDeg, Id::kAzMaxDeg, Id::kAzContinuous}) &&
      slow_zone_too_long(detail_, sizeof detail_, get(Id::kAzSlowZoneDeg), az_travel_deg, az))
    return out_of_range;
  if (el_on && touched({Id::kElSlowZoneDeg, Id::kElMinDeg, Id::kElMaxDeg}) &&
      slow_zone_too_long(detail_, sizeof detail_, get(Id::kElSlowZoneDeg), el.max_deg - el.min_deg,
                         el))
    return out_of_range;
  return {};
}

Rejection Settings::check_dependent(const Settings& before) const {
  return check_dependent_rules([&](std::initializer_list<Id> ids) {
    for (const Id id : ids)
      if (!same_value(id, before)) return true;
    return false;
  });
}

Rejection Settings::check_dependent(Id changed) const {
  return check_dependent_rules([&](std::initializer_list<Id> ids) {
    for (const Id id : ids)
      if (id == changed) return true;
    return false;
  });
}

Rejection Settings::save_from_text(Id id, std::string_view text) {
  const double before = get(id);
  const bool numeric = !is_text(id);
  const Rejection r = update_from_text(id, text);
  if (r.error != Error::kOk) return r;
  const Rejection rule = check_dependent(id);
  if (rule.error == Error::kOk) return {};
  // The rules are about numbers only: undo the one number written.
  if (numeric) set(id, before);
  return rule;
}

}  // namespace rotord::settings
