#include "util/error.hpp"

namespace rotord {

const char* error_name(Error error) {
  switch (error) {
    case Error::kOk:
      return "OK";
    case Error::kInvalidArgument:
      return "INVALID ARGUMENT";
    case Error::kOutOfRange:
      return "OUT OF RANGE";
    case Error::kNotSupported:
      return "NOT SUPPORTED";
    case Error::kFaulted:
      return "FAULT";
    case Error::kLimit:
      return "LIMIT";
    case Error::kBusy:
      return "BUSY";
    case Error::kNotFound:
      return "NOT FOUND";
    case Error::kStorage:
      return "STORAGE";
    case Error::kStowed:
      return "STOWED";
  }
  return "UNKNOWN";
}

}  // namespace rotord
