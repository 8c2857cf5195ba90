#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "util/error.hpp"

namespace rotord::settings {

enum class Type : std::uint8_t { kFloat, kInt, kBool, kEnum };

enum Flags : std::uint8_t { kNone = 0, kRestart = 1 };

enum class Id : std::uint16_t {
#define SETTING(id, ...) id,
#include "settings/settings_table.def"
#undef SETTING
  kCount
};

inline constexpr std::size_t kCount = static_cast<std::size_t>(Id::kCount);

/// One row of the settings table.
struct Def {
  const char* key;
  Type type;
  const char* unit;
  double min;
  double max;
  double default_value;
  const char* group;
  std::uint8_t flags;
  const char* choices;  ///< enum names separated by '|', empty otherwise
  const char* help;
};

const Def& def(Id id);
std::optional<Id> find(std::string_view key);

/// The number of choices of an enum setting and the name of one of them.
int choice_count(Id id);
std::string_view choice_name(Id id, int index);

/// Result of a rejected value, with a human-readable reason for forms and
/// protocol errors.
struct Rejection {
  Error error = Error::kOk;
  const char* reason = "";
};

/// The values of every setting. Plain data (an array of doubles), so a copy is
/// cheap and the controller can compare a candidate set before applying it.
class Settings {
 public:
  Settings();

  double get(Id id) const { return values_[static_cast<std::size_t>(id)]; }
  float f(Id id) const { return static_cast<float>(get(id)); }
  int i(Id id) const { return static_cast<int>(get(id)); }
  bool b(Id id) const { return get(id) != 0.0; }

  /// Sets a value after checking type and range; nothing changes on error.
  Rejection set(Id id, double value);
  /// Parses text the way every front end sends it: numbers ("12.5", "-3"),
  /// booleans ("true"/"false"/"1"/"0"), enum names or indices.
  Rejection set_from_text(Id id, std::string_view text);
  /// Checks the rules that span several settings (min below max, two
  /// distinct calibration points, no two functions on one pin...). A reason
  /// that names values (pin conflicts) points into this object and stays
  /// valid until the next check on it.
  Rejection check_consistency() const;

  void reset_to_defaults();
  /// Bumps on every change; the controller re-derives its configuration when it moves.
  std::uint32_t revision() const { return revision_; }

  /// Formats a value for text protocols and files ("12.5", "true", "relay").
  static std::size_t format(Id id, double value, char* out, std::size_t capacity);

 private:
  double values_[kCount];
  std::uint32_t revision_ = 0;
  // The text of the last rule that names keys and values, e.g. "pins.btn_cw
  // and pins.az_ma3 both use GPIO 2" (the core has no mutable globals).
  mutable char detail_[160] = {};
};

/// Checks a value against a row without storing it.
Rejection validate(Id id, double value);

}  // namespace rotord::settings
