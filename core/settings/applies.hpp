#pragma once
#include <cstdint>
#include <string_view>

#include "settings/settings.hpp"

namespace rotord::settings {

/// What the firmware drives: the rows of the other platforms (the Pico W's
/// pins, the Raspberry Pi's gpiod lines, the Wi-Fi, the Linux-only MQTT TLS
/// and TLE refresh) do not apply to it. kUnknown: every platform's rows
/// apply (a reader that was not told).
enum class Platform : std::uint8_t { kUnknown, kPicoW, kGpiod, kSim };

/// The name a condition uses ("pico_w", "gpiod", "sim"; "" for kUnknown),
/// also GET /api/settings/schema's "platform".
std::string_view platform_name(Platform platform);

/// Whether the row's condition (settings::condition) holds for these values
/// on this platform: what the settings form shows. A row whose condition
/// cannot be read applies (never hides a setting by mistake; the table's
/// test refuses such a condition).
bool applies(Id id, const Settings& values, Platform platform);

/// Why a condition cannot be read (an unknown key, a choice the key does not
/// have, a choice asked of a row that is no enum), or nullptr when it can. The table's test
/// runs it on every row.
const char* condition_error(std::string_view condition);

}  // namespace rotord::settings
