#include "legacy_profile_guess.hpp"

namespace rotord::linux_port {
namespace {

bool holds_every_override(const settings::Settings& values, const sim::Profile& profile) {
  for (const auto& o : profile.overrides) {
    const auto id = settings::find(o.key);
    if (!id || values.get(*id) != o.value) return false;
  }
  return true;
}

}  // namespace

const settings::Settings& LegacyProfileGuess::base_of(const settings::Settings& file_values) {
  recognised_ = nullptr;
  if (holds_every_override(file_values, current_)) {
    recognised_ = &current_;
  } else {
    for (const sim::Profile* p : sim::all_profiles()) {
      if (holds_every_override(file_values, *p)) {
        recognised_ = p;
        break;
      }
    }
  }
  base_.reset_to_defaults();
  if (recognised_ != nullptr) {
    for (const auto& o : recognised_->overrides)
      base_.set(*settings::find(o.key), o.value);  // the profile was checked at start-up
  }
  return base_;
}

}  // namespace rotord::linux_port
