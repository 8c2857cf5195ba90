#pragma once
// Bases for testing the stored user's layer (settings_layers.hpp) at its
// largest: every setting changed.
#include "settings/settings.hpp"

namespace rotord::testing {

/// A base in which every setting that can differs from `values`: numbers at
/// the other end of their range, texts empty where `values` has one. Stored
/// over it, `values` writes (nearly) every row, the worst case for buffers.
inline settings::Settings differs_everywhere(const settings::Settings& values) {
  settings::Settings base = values;
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<settings::Id>(n);
    const settings::Def& d = settings::def(id);
    if (settings::is_text(id)) {
      if (!values.text(id).empty()) base.set_text(id, "");
    } else {
      base.set(id, values.get(id) != d.max ? d.max : d.min);
    }
  }
  return base;
}

}  // namespace rotord::testing
