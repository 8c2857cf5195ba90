#pragma once
#include <cstddef>
#include <optional>

#include "settings/settings.hpp"

namespace rotord::settings {

/// GPIO value of a pins.* row that is not wired.
inline constexpr int kNoPin = -1;

/// True for the rows of the "Pins" group (keys "pins.*").
bool is_pin(Id id);

/// The first rule the pins.* settings break, described in `detail` (both keys
/// and the GPIO, e.g. "pins.btn_cw and pins.az_ma3 both use GPIO 2"), or
/// nullopt when they are fine. Rules: no two functions on one GPIO; GPIO 23 to
/// 25 are the Pico W's Wi-Fi chip; pots on an ADC pin (26..28); the I2C pins
/// an SDA/SCL pair of one RP2040 I2C block.
std::optional<Error> check_pins(const Settings& s, char* detail, std::size_t capacity);

}  // namespace rotord::settings
