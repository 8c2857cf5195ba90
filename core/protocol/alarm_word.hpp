#pragma once
#include "util/error.hpp"

namespace rotord::protocol {

/// The one upper-case word Easycomm's `AL<REASON>` and seed's
/// `$ERR,<REASON>` give for a refusal (docs/protocols/easycomm.md, seed.md):
/// RANGE, FAULT, LIMIT, STOWED, UNSUPPORTED, and SYNTAX for anything the
/// words do not name. One table, so the two replies cannot drift apart.
const char* alarm_word(Error e);

}  // namespace rotord::protocol
