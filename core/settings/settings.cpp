#include "settings/settings.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "settings/gpiod_rules.hpp"
#include "settings/pin_rules.hpp"
#include "settings/pot_table.hpp"
#include "util/text.hpp"

namespace rotord::settings {
namespace {

constexpr Def kDefs[] = {
#define SETTING(id, key, type, unit, min, max, def, group, flags, choices, help) \
  {key, Type::type, unit, min, max, def, group, flags, choices, help},
#include "settings/settings_table.def"
#undef SETTING
};
static_assert(sizeof(kDefs) / sizeof(kDefs[0]) == kCount);

}  // namespace

const Def& def(Id id) {
  return kDefs[static_cast<std::size_t>(id)];
}

std::optional<Id> find(std::string_view key) {
  for (std::size_t n = 0; n < kCount; ++n) {
    if (key == kDefs[n].key) return static_cast<Id>(n);
  }
  return std::nullopt;
}

int choice_count(Id id) {
  const char* choices = def(id).choices;
  if (*choices == '\0') return 0;
  int count = 1;
  for (const char* c = choices; *c; ++c)
    if (*c == '|') ++count;
  return count;
}

std::string_view choice_name(Id id, int index) {
  std::string_view rest = def(id).choices;
  for (int n = 0; n < index; ++n) {
    std::size_t bar = rest.find('|');
    if (bar == std::string_view::npos) return {};
    rest.remove_prefix(bar + 1);
  }
  return rest.substr(0, rest.find('|'));
}

Rejection validate(Id id, double value) {
  const Def& d = def(id);
  if (!std::isfinite(value)) return {Error::kInvalidArgument, "not a number"};
  if (d.type != Type::kFloat && value != std::floor(value))
    return {Error::kInvalidArgument, "must be a whole number"};
  if (value < d.min || value > d.max) return {Error::kOutOfRange, "outside the allowed range"};
  return {};
}

Settings::Settings() {
  reset_to_defaults();
}

void Settings::reset_to_defaults() {
  for (std::size_t n = 0; n < kCount; ++n) values_[n] = kDefs[n].default_value;
  ++revision_;
}

Rejection Settings::set(Id id, double value) {
  Rejection r = validate(id, value);
  if (r.error != Error::kOk) return r;
  double& slot = values_[static_cast<std::size_t>(id)];
  if (slot != value) {
    slot = value;
    ++revision_;
  }
  return {};
}

Rejection Settings::set_from_text(Id id, std::string_view text) {
  text = text::trim(text);
  const Def& d = def(id);
  if (d.type == Type::kBool) {
    if (text == "true" || text == "on" || text == "1") return set(id, 1);
    if (text == "false" || text == "off" || text == "0") return set(id, 0);
    return {Error::kInvalidArgument, "expected true or false"};
  }
  if (d.type == Type::kEnum) {
    for (int n = 0; n < choice_count(id); ++n)
      if (choice_name(id, n) == text) return set(id, n);
  }
  double value = 0;
  if (!text::parse_double(text, value)) return {Error::kInvalidArgument, "not a number"};
  return set(id, value);
}

Rejection Settings::check_consistency() const {
  if (get(Id::kAzMinDeg) >= get(Id::kAzMaxDeg))
    return {Error::kOutOfRange, "az.min_deg must be below az.max_deg"};
  if (get(Id::kAzMaxDeg) - get(Id::kAzMinDeg) > 720)
    return {Error::kOutOfRange, "azimuth travel cannot exceed 720 deg"};
  if (get(Id::kElMinDeg) >= get(Id::kElMaxDeg))
    return {Error::kOutOfRange, "el.min_deg must be below el.max_deg"};
  if (get(Id::kAzPotCalLoCounts) == get(Id::kAzPotCalHiCounts) ||
      get(Id::kAzPotCalLoDeg) == get(Id::kAzPotCalHiDeg))
    return {Error::kOutOfRange, "the two azimuth calibration points must differ"};
  if (get(Id::kElPotCalLoCounts) == get(Id::kElPotCalHiCounts) ||
      get(Id::kElPotCalLoDeg) == get(Id::kElPotCalHiDeg))
    return {Error::kOutOfRange, "the two elevation calibration points must differ"};
  for (const AxisId axis : {AxisId::kAz, AxisId::kEl}) {
    const PotCalibration cal = pot_calibration_from(*this, axis);
    const int bad = cal.first_bad_point();
    if (bad < 0) continue;
    std::snprintf(detail_, sizeof detail_,
                  "%s: counts and degrees must rise or fall together from %s through the extra "
                  "points to %s",
                  pot_point_key(axis, bad, cal.count), pot_point_key(axis, 0, cal.count),
                  pot_point_key(axis, cal.count - 1, cal.count));
    return {Error::kOutOfRange, detail_};
  }
  if (get(Id::kAzPwmSlowDuty) > get(Id::kAzPwmFastDuty) ||
      get(Id::kElPwmSlowDuty) > get(Id::kElPwmFastDuty))
    return {Error::kOutOfRange, "the slow PWM duty must not exceed the fast duty"};
  if (const auto pins = check_pins(*this, detail_, sizeof detail_)) return {*pins, detail_};
  if (const auto lines = check_gpiod_lines(*this, detail_, sizeof detail_))
    return {*lines, detail_};
  if (get(Id::kMagXMin) >= get(Id::kMagXMax) || get(Id::kMagYMin) >= get(Id::kMagYMax))
    return {Error::kOutOfRange, "mag.x_min and mag.y_min must be below mag.x_max and mag.y_max"};
  if (i(Id::kAzSensor) == 2 && (i(Id::kPinI2cSda) == kNoPin || i(Id::kPinI2cScl) == kNoPin))
    return {Error::kOutOfRange, "az.sensor = mag needs pins.i2c_sda and pins.i2c_scl"};
  if (b(Id::kButtonsEnabled) && (i(Id::kPinBtnCw) == kNoPin || i(Id::kPinBtnCcw) == kNoPin))
    return {Error::kOutOfRange, "buttons.enabled needs pins.btn_cw and pins.btn_ccw"};
  return {};
}

std::size_t Settings::format(Id id, double value, char* out, std::size_t capacity) {
  const Def& d = def(id);
  int n = 0;
  switch (d.type) {
    case Type::kBool:
      n = std::snprintf(out, capacity, "%s", value != 0.0 ? "true" : "false");
      break;
    case Type::kEnum: {
      std::string_view name = choice_name(id, static_cast<int>(value));
      n = std::snprintf(out, capacity, "%.*s", static_cast<int>(name.size()), name.data());
      break;
    }
    case Type::kInt:
      n = std::snprintf(out, capacity, "%ld", static_cast<long>(value));
      break;
    case Type::kFloat:
      n = std::snprintf(out, capacity, "%.6g", value);
      break;
  }
  if (n < 0) return 0;
  return static_cast<std::size_t>(n) < capacity ? static_cast<std::size_t>(n) : capacity - 1;
}

}  // namespace rotord::settings
