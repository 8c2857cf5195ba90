#pragma once
// A command's arguments as JSON: the REST body and the MQTT payload are the
// same document, read here once.
#include <cstddef>
#include <span>
#include <string_view>

#include "command/result.hpp"
#include "json/json_members.hpp"
#include "json/json_reader.hpp"

namespace rotord::command {

/// One member of a small command body, checked against what the command
/// takes (read by the one loop every small body is read with).
using Member = web::JsonMember;

/// Reads `body` (empty = {}) into `members`; false with `refusal` a 400 on
/// bad JSON, an unknown member or a member of the wrong type. (The caller's
/// Result, not a second one: each is ~250 bytes of the Pico W's stack.)
bool read_members(std::string_view body, std::span<Member> members, Result& refusal);

/// The place a body names ({"locator"} or {"lat","lon"}, "path"); kOk or a 400.
Result read_place(std::string_view body, PlaceQuery& q);

/// A preset body: {"name"} (name_only), or {"name","az","long_path"}.
struct PresetBody {
  char name[settings::kPresetNameMaxBytes + 1] = {};
  bool has_name = false;
  bool has_az = false;
  double az_deg = 0;
  bool long_path = false;
};
/// nullptr, or why the body is not one.
const char* read_preset_body(std::string_view body, PresetBody& b, bool name_only);

}  // namespace rotord::command
