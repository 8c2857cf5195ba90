#pragma once
#include <cstddef>
#include <optional>

#include "settings/settings.hpp"

namespace rotord::settings {

/// True for the line rows of the "Raspberry Pi" group (keys "gpiod.az_*",
/// "gpiod.el_*", "gpiod.btn_*": the ones whose unit is "line").
bool is_gpiod_line(Id id);

/// The first pair of gpiod.* lines that share an offset of the chip, or of
/// pwm.* H-bridge halves that share a PWM channel, described in `detail` with
/// both keys and the number (e.g. "gpiod.az_l1 and gpiod.btn_cw both use line
/// 5"), or nullopt. Kept apart from the Pico's pin rules: these
/// are offsets of a Linux gpiochip, with none of the RP2040's restrictions.
std::optional<Error> check_gpiod_lines(const Settings& s, char* detail, std::size_t capacity);

}  // namespace rotord::settings
