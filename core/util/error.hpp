#pragma once
#include <cstdint>

namespace rotord {

/// Errors are values (the core builds with -fno-exceptions). Every protocol maps
/// these onto its own error replies.
enum class Error : std::uint8_t {
  kOk = 0,
  kInvalidArgument,  ///< unparsable or wrong type
  kOutOfRange,       ///< parsable but outside the allowed range / mechanical limits
  kNotSupported,     ///< e.g. an elevation command on an azimuth-only rotator
  kFaulted,          ///< an axis has a latched fault; RESET first
  kLimit,            ///< the requested direction is blocked by a limit
  kBusy,             ///< resource exhausted (too many clients, queue full)
  kNotFound,         ///< unknown key or command
  kStorage,          ///< persistence failed
  kStowed,           ///< the wind stow refuses moves until calm (or an override)
};

const char* error_name(Error error);

}  // namespace rotord
