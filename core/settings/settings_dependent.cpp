// The rules checked when a value is saved (Settings::check_dependent): values
// that depend on each other, so that a save cannot leave a setting that
// cannot work (issue 23: park.az_deg 500 on a 0..450 rotator was saved, and
// PARK then failed). Each message names both settings and their values.
#include <cstdio>
#include <initializer_list>

#include "settings/settings.hpp"

namespace rotord::settings {

template <typename Touched>
Rejection Settings::check_dependent_rules(Touched touched) const {
  const bool continuous = b(Id::kAzContinuous);
  const double az_min = get(Id::kAzMinDeg);
  const double az_max = get(Id::kAzMaxDeg);
  const double el_min = get(Id::kElMinDeg);
  const double el_max = get(Id::kElMaxDeg);
  // A continuous azimuth takes any bearing: the park azimuth wraps.
  if (!continuous && touched({Id::kParkAzDeg, Id::kAzMinDeg, Id::kAzMaxDeg, Id::kAzContinuous})) {
    const double park = get(Id::kParkAzDeg);
    if (park < az_min || park > az_max) {
      std::snprintf(detail_, sizeof detail_,
                    "park.az_deg %g is outside the azimuth travel az.min_deg..az.max_deg "
                    "(%g..%g): PARK could not go there",
                    park, az_min, az_max);
      return {Error::kOutOfRange, detail_};
    }
  }
  if (b(Id::kElEnabled) &&
      touched({Id::kParkElDeg, Id::kElMinDeg, Id::kElMaxDeg, Id::kElEnabled})) {
    const double park = get(Id::kParkElDeg);
    if (park < el_min || park > el_max) {
      std::snprintf(detail_, sizeof detail_,
                    "park.el_deg %g is outside the elevation travel el.min_deg..el.max_deg "
                    "(%g..%g): PARK could not go there",
                    park, el_min, el_max);
      return {Error::kOutOfRange, detail_};
    }
  }
  // Wind stow (docs/care.md): checked once a source is set, so an unused
  // default never blocks a change of the travel.
  const bool wind_on = i(Id::kWindSource) != 0;
  if (wind_on && !continuous &&
      touched(
          {Id::kWindStowAzDeg, Id::kWindSource, Id::kAzMinDeg, Id::kAzMaxDeg, Id::kAzContinuous})) {
    const double stow = get(Id::kWindStowAzDeg);
    if (stow < az_min || stow > az_max) {
      std::snprintf(detail_, sizeof detail_,
                    "wind.stow_az_deg %g is outside the azimuth travel az.min_deg..az.max_deg "
                    "(%g..%g): a wind stow could not go there",
                    stow, az_min, az_max);
      return {Error::kOutOfRange, detail_};
    }
  }
  if (wind_on && touched({Id::kWindCalmMps, Id::kWindStowMps, Id::kWindSource}) &&
      get(Id::kWindCalmMps) > get(Id::kWindStowMps)) {
    std::snprintf(detail_, sizeof detail_,
                  "wind.calm_mps %g is above wind.stow_mps %g: the wind could be calm and a "
                  "storm at once",
                  get(Id::kWindCalmMps), get(Id::kWindStowMps));
    return {Error::kOutOfRange, detail_};
  }
  // A slow zone as long as the travel makes every move a slow one.
  const double az_travel = continuous ? 360.0 : az_max - az_min;
  if (touched({Id::kAzSlowZoneDeg, Id::kAzMinDeg, Id::kAzMaxDeg, Id::kAzContinuous}) &&
      get(Id::kAzSlowZoneDeg) >= az_travel) {
    std::snprintf(
        detail_, sizeof detail_,
        "az.slow_zone_deg %g must be shorter than the azimuth travel az.min_deg..az.max_deg "
        "(%g deg)",
        get(Id::kAzSlowZoneDeg), az_travel);
    return {Error::kOutOfRange, detail_};
  }
  if (b(Id::kElEnabled) && touched({Id::kElSlowZoneDeg, Id::kElMinDeg, Id::kElMaxDeg}) &&
      get(Id::kElSlowZoneDeg) >= el_max - el_min) {
    std::snprintf(detail_, sizeof detail_,
                  "el.slow_zone_deg %g must be shorter than the elevation travel "
                  "el.min_deg..el.max_deg (%g deg)",
                  get(Id::kElSlowZoneDeg), el_max - el_min);
    return {Error::kOutOfRange, detail_};
  }
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
