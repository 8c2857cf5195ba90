#pragma once
// The JSON pieces the tracking endpoints share (track_api.cpp, tle_api.cpp).
#include <cstdint>
#include <string_view>

#include "json/json_writer.hpp"
#include "tracking/pass_finder.hpp"

namespace rotord::web {

/// `name`: the time as ISO 8601 UTC to the second, or null.
void write_utc(JsonWriter& w, std::string_view name, std::int64_t unix_ms);
/// One pass: rise, culmination and set.
void write_pass(JsonWriter& w, const tracking::Pass& p);

}  // namespace rotord::web
