#include "settings/preset.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::settings {

const char* check_preset_name(std::string_view name) {
  if (name.empty()) return "a preset needs a name";
  if (name.size() > kPresetNameMaxBytes) return "a preset name is at most 20 bytes";
  // No quotes or backslashes: each stored row stays its own length in the
  // settings document (JSON escapes would double them; the flash slot is 8 KB).
  for (char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '"' || c == '\\')
      return "a preset name has no control characters, quotes or backslashes";
  if (name.front() == ' ' || name.back() == ' ')
    return "a preset name neither starts nor ends with a space";
  return nullptr;
}

const char* parse_preset(std::string_view text, Preset& out) {
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos || colon == 0)
    return "not <az_deg>[L]:<name> (e.g. 45:EU or 150L:JA)";
  std::string_view az_text = rotord::text::slice(text, 0, colon);
  out.long_path = az_text.back() == 'L' || az_text.back() == 'l';
  if (out.long_path) az_text.remove_suffix(1);
  char number[16];
  if (az_text.empty() || az_text.size() >= sizeof number)
    return "the heading is not a number of degrees";
  std::memcpy(number, az_text.data(), az_text.size());
  number[az_text.size()] = '\0';
  char* end = nullptr;
  const double az = std::strtod(number, &end);
  if (end != number + az_text.size() || !std::isfinite(az))
    return "the heading is not a number of degrees";
  if (az < 0.0 || az >= 360.0) return "the heading is outside 0..360";
  const std::string_view name = rotord::text::slice(text, colon + 1);
  if (const char* why = check_preset_name(name)) return why;
  out.az_deg = az;
  std::memcpy(out.name, name.data(), name.size());
  out.name[name.size()] = '\0';
  return nullptr;
}

std::size_t format_preset(const Preset& p, char* buf, std::size_t cap) {
  const int n = std::snprintf(buf, cap, "%.1f%s:%s", p.az_deg, p.long_path ? "L" : "", p.name);
  return n < 0 ? 0 : static_cast<std::size_t>(n) < cap ? static_cast<std::size_t>(n) : cap - 1;
}

Id preset_id(std::size_t index) {
  return static_cast<Id>(static_cast<std::size_t>(Id::kPreset1) + index);
}

std::optional<std::size_t> find_preset(const Settings& s, std::string_view name, Preset* out) {
  for (std::size_t n = 0; n < kPresetCount; ++n) {
    Preset p;
    if (parse_preset(s.text(preset_id(n)), p) != nullptr) continue;
    if (!text::iequals(p.name, name)) continue;
    if (out != nullptr) *out = p;
    return n;
  }
  return std::nullopt;
}

}  // namespace rotord::settings
