#include "protocol/alarm_word.hpp"

namespace rotord::protocol {

const char* alarm_word(Error e) {
  switch (e) {
    case Error::kOutOfRange:
      return "RANGE";
    case Error::kFaulted:
      return "FAULT";
    case Error::kLimit:
      return "LIMIT";
    case Error::kStowed:
      return "STOWED";
    case Error::kNotSupported:
      return "UNSUPPORTED";
    default:
      return "SYNTAX";
  }
}

}  // namespace rotord::protocol
