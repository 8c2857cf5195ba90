#pragma once
// The member readers the settings codec shares with the start-up loader
// (settings_load.cpp): internal to core/json.
#include <string_view>

#include "json/json_reader.hpp"
#include "settings/settings.hpp"

namespace rotord::web::detail {

/// Checks one member against its row and stores it in `candidate` (which is
/// unchanged on failure); returns the reason on failure.
const char* apply_member(settings::Id id, const JsonValue& v, settings::Settings& candidate);

/// Reads settings::kVersionKey's value; the reason when it is not a version
/// this build reads.
const char* read_version(const JsonValue& v, int& version);

/// The document's settings::kVersionKey, 1 when it has none (or is no
/// object).
int stored_version(std::string_view json);

}  // namespace rotord::web::detail
