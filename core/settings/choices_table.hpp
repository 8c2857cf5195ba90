#pragma once
// Each setting's choices ('|'-separated; an enum's names), as constants, for
// checks at compile time in the layers above (protocol_registry.cpp checks
// usb.personality's against the protocol rows). Apart from settings.hpp so
// that only those files include it; never emitted (constant expressions).
#include <cstddef>

#include "settings/settings.hpp"

namespace rotord::settings {

inline constexpr const char* kChoicesOf[] = {
#define SETTING(id, key, type, unit, min, max, def, group, flags, choices, ...) choices,
#include "settings/settings_table.def"
#undef SETTING
};
static_assert(sizeof kChoicesOf / sizeof kChoicesOf[0] == kCount, "one entry per row");

/// The choices of `id` (empty when it has none).
constexpr const char* choices_of(Id id) {
  return kChoicesOf[static_cast<std::size_t>(id)];
}

}  // namespace rotord::settings
