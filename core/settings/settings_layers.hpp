#pragma once
#include <bitset>

#include "settings/settings.hpp"

namespace rotord::settings {

// The settings in force are layered: the table's defaults, then the
// platform's own (a simulator profile, the Pico W's build-time Wi-Fi), then
// the user's changes on top. Only the user's layer is stored, so a file saved
// under one simulator profile does not carry that profile's geometry into
// another, while a value the user changed wins under every profile.

/// A set of settings, one bit per table row. Indexed with [] in the core:
/// test() and set() check the position and throw std::out_of_range, which
/// links the exception runtime into the firmware (cmake/check-no-exceptions.cmake).
using KeySet = std::bitset<kCount>;

/// The stored document's format: 2 holds the user's layer only and names its
/// version under kVersionKey; a document without the key is a version-1
/// file, written before layering with every setting in it.
inline constexpr int kStoredVersion = 2;
inline constexpr const char* kVersionKey = "settings_version";

/// The settings whose value differs between `values` and `base`: the user's
/// layer of `values` over `base`.
KeySet user_layer(const Settings& values, const Settings& base);

/// Builds `base` with the `keys` of `user` on top into `out`, then checks the
/// cross-setting rules. On a rejection `out` is left as it was.
/// `scratch` holds the candidate, so the caller decides where it lives.
Rejection apply_user_layer(const Settings& base, const Settings& user, const KeySet& keys,
                           Settings& scratch, Settings& out);

}  // namespace rotord::settings
