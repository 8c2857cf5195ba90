#pragma once
#include "util/error.hpp"

namespace rotord::protocol {

/// The words a line protocol's refusal gives: a fault, a limit and the wind
/// stow by their shared names (FAULT, LIMIT, STOWED: error_name), the rest
/// in the protocol's own words. One rule, so the protocols cannot drift
/// apart on which refusals have a word of their own.
struct RefusalWords {
  const char* out_of_range;
  const char* not_supported;
  const char* other;  ///< anything the words do not name
};
const char* refusal_word(Error e, const RefusalWords& words);

/// The one upper-case word Easycomm's `AL<REASON>` and seed's
/// `$ERR,<REASON>` give for a refusal (docs/protocols/easycomm.md, seed.md):
/// RANGE, FAULT, LIMIT, STOWED, UNSUPPORTED, and SYNTAX for anything the
/// words do not name.
const char* alarm_word(Error e);

}  // namespace rotord::protocol
