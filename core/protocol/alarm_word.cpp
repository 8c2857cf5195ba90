#include "protocol/alarm_word.hpp"

namespace rotord::protocol {

const char* refusal_word(Error e, const RefusalWords& words) {
  switch (e) {
    case Error::kFaulted:
    case Error::kLimit:
    case Error::kStowed:
      return error_name(e);
    case Error::kOutOfRange:
      return words.out_of_range;
    case Error::kNotSupported:
      return words.not_supported;
    default:
      return words.other;
  }
}

const char* alarm_word(Error e) {
  return refusal_word(e, {"RANGE", "UNSUPPORTED", "SYNTAX"});
}

}  // namespace rotord::protocol
