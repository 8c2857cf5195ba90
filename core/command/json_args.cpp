#include "command/json_args.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace rotord::command {

using web::JsonObjectReader;
using web::JsonType;
using web::JsonValue;

bool read_members(std::string_view body, std::span<Member> members, Result& refusal) {
  // Why goes straight into the refusal's message: no second buffer on the
  // Pico W's stack. The refusal is then a plain 400 with it, nothing else.
  if (web::read_members(body, members, refusal.message, sizeof refusal.message)) return true;
  refusal = refused(Status::kBadRequest, refusal.message);
  return false;
}

namespace {

/// The place a body names; nullptr, or why not.
const char* place_from_body(std::string_view body, PlaceQuery& q, char* why_buf, std::size_t cap) {
  JsonObjectReader reader(body);
  if (!reader.valid()) return "invalid JSON";
  std::string_view key;
  JsonValue value;
  bool has_locator = false, has_lat = false, has_lon = false;
  double lat = 0, lon = 0;
  char path[8] = "short";
  while (reader.next(key, value)) {
    const bool number = value.type == JsonType::kNumber;
    const bool text = value.type == JsonType::kString;
    if (key == "locator" && text) {
      if (const char* why = place_from_locator(value.text, q)) return why;
      has_locator = true;
    } else if (key == "lat" && number) {
      lat = value.number;
      has_lat = true;
    } else if (key == "lon" && number) {
      lon = value.number;
      has_lon = true;
    } else if (key == "path" && text) {
      // A word longer than "short" is no path: kept as "?" to be refused.
      const std::size_t n = value.text.size() < sizeof path ? value.text.size() : 0;
      if (n > 0) std::memcpy(path, value.text.data(), n);
      path[n] = n == 0 ? '?' : '\0';
      path[n == 0 ? 1 : n] = '\0';
    } else {
      std::snprintf(why_buf, cap, "'%.*s' is not a member here (locator, lat, lon, path)",
                    static_cast<int>(key.size() > 24 ? 24 : key.size()), key.data());
      return why_buf;
    }
  }
  if (!reader.valid()) return "invalid JSON";
  if (has_locator == (has_lat || has_lon)) return "give locator, or lat and lon";
  if (!has_locator) {
    if (!has_lat || !has_lon) return "give both lat and lon";
    if (const char* why = place_from_lat_lon(lat, lon, q)) return why;
  }
  return place_path(path, q);
}

}  // namespace

Result read_place(std::string_view body, PlaceQuery& q) {
  char why_buf[80];
  if (const char* why = place_from_body(body, q, why_buf, sizeof why_buf))
    return refused(Status::kBadRequest, why);
  return {};
}

const char* read_preset_body(std::string_view body, PresetBody& b, bool name_only) {
  JsonObjectReader reader(body);
  if (!reader.valid()) return "invalid JSON";
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    if (key == "name" && value.type == JsonType::kString) {
      if (value.truncated) return "a preset name is at most 20 bytes";
      if (const char* why = settings::check_preset_name(value.text)) return why;
      std::memcpy(b.name, value.text.data(), value.text.size());
      b.name[value.text.size()] = '\0';
      b.has_name = true;
    } else if (!name_only && key == "az" && value.type == JsonType::kNumber) {
      b.az_deg = value.number;
      b.has_az = true;
    } else if (!name_only && key == "long_path" && value.type == JsonType::kBool) {
      b.long_path = value.boolean;
    } else {
      return name_only ? "the body is {\"name\": ...}"
                       : "the body is {\"name\": ..., \"az\": degrees, \"long_path\": bool}";
    }
  }
  if (!reader.valid()) return "invalid JSON";
  if (!b.has_name) return "give the preset's name";
  if (!name_only && !b.has_az) return "give az (degrees, 0..360)";
  if (!name_only && (!std::isfinite(b.az_deg) || b.az_deg < 0.0 || b.az_deg > 360.0))
    return "az is outside 0..360";
  return nullptr;
}

}  // namespace rotord::command
