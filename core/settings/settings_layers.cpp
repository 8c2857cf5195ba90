#include "settings/settings_layers.hpp"

namespace rotord::settings {

KeySet user_layer(const Settings& values, const Settings& base) {
  KeySet keys;
  for (std::size_t n = 0; n < kCount; ++n)
    if (!values.same_value(static_cast<Id>(n), base)) keys[n] = true;
  return keys;
}

Rejection apply_user_layer(const Settings& base, const Settings& user, const KeySet& keys,
                           Settings& scratch, Settings& out) {
  scratch = base;
  for (std::size_t n = 0; n < kCount; ++n)
    if (keys[n]) scratch.copy_value(static_cast<Id>(n), user);
  // Each layer was valid on its own; a user's range may still clash with a
  // profile it was not made under (a minimum above the new maximum).
  const Rejection rule = scratch.check_consistency();
  if (rule.error != Error::kOk) return rule;
  out = scratch;
  return {};
}

}  // namespace rotord::settings
