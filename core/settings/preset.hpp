#pragma once
// Presets: named headings stored in the settings rows preset.1..preset.16 as
// "<az_deg>[L]:<name>" (docs/web_api.md, "Presets"). One parser for every
// reader (the settings check, REST, the console, MQTT), so a row the
// settings accept is a row every one of them can turn to.
#include <cstddef>
#include <optional>
#include <string_view>

#include "settings/settings.hpp"

namespace rotord::settings {

inline constexpr std::size_t kPresetCount = 16;
inline constexpr std::size_t kPresetNameMaxBytes = 20;

struct Preset {
  double az_deg = 0;       ///< compass heading, 0..360
  bool long_path = false;  ///< shown as a long-path heading
  char name[kPresetNameMaxBytes + 1] = {};
};

/// Parses a stored row; nullptr on success, else why it is not a preset.
const char* parse_preset(std::string_view text, Preset& out);
/// Writes `p` as a stored row into `buf` (at least 32 bytes); its length.
std::size_t format_preset(const Preset& p, char* buf, std::size_t cap);
/// Checks a name as given by a client: nullptr if fine, else why not.
const char* check_preset_name(std::string_view name);

/// The setting id of preset slot `index` (0..15).
Id preset_id(std::size_t index);
/// The slot whose preset is called `name` (case-insensitive), if any.
std::optional<std::size_t> find_preset(const Settings& s, std::string_view name,
                                       Preset* out = nullptr);

}  // namespace rotord::settings
