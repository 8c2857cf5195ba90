#pragma once
#include <cstddef>
#include <span>
#include <string_view>

#include "settings/settings.hpp"

namespace rotord::settings {

/// One published figure of a rotator model and where it comes from.
/// `source` null: no maker's figure was found; applying the model leaves the
/// setting as it is, and self-commissioning measures it.
struct ModelFigure {
  double value = 0.0;
  const char* source = nullptr;
  constexpr bool known() const { return source != nullptr; }
};

/// One row of the rotator model list (docs/rotator_models.md prints the
/// same rows with their sources). Values are in the settings' own units:
/// drive and sensor are the az.drive / az.sensor choice indices.
struct RotatorModel {
  const char* id;    ///< what `setup model <id>` and the REST API take
  const char* name;  ///< the maker's name
  ModelFigure drive;
  ModelFigure sensor;
  ModelFigure az_min_deg;
  ModelFigure az_max_deg;
  ModelFigure has_el;
  ModelFigure el_min_deg;
  ModelFigure el_max_deg;
  ModelFigure az_speed_deg_s;
  ModelFigure el_speed_deg_s;
  ModelFigure has_brake;
  ModelFigure brake_release_ms;
  ModelFigure brake_engage_ms;
  ModelFigure reverse_dead_ms;
  const char* note;  ///< what the owner must know that no setting says
};

/// Every model, in the order the set-up page lists them ("other" last).
std::span<const RotatorModel> rotator_models();
/// nullptr when no model has this id.
const RotatorModel* find_rotator_model(std::string_view id);

/// The settings a model's known figures fill, in a fixed order, paired with
/// the figure (for the docs, the console and the set-up page).
struct ModelSetting {
  Id id;
  const ModelFigure* figure;
};
inline constexpr std::size_t kModelSettingCount = 14;
/// Writes the rows a model fills into `out` (unknown figures included, with
/// figure->known() false) and returns how many (kModelSettingCount, fewer
/// for an azimuth-only model, which has no elevation rows).
std::size_t model_settings(const RotatorModel& model, ModelSetting* out, std::size_t capacity);

/// Fills `s` with the model's known figures through Settings::set and
/// check_consistency on a scratch copy: either every figure is taken or,
/// on a rejection (its reason returned), `s` is left unchanged.
Rejection apply_rotator_model(const RotatorModel& model, Settings& s);

}  // namespace rotord::settings
