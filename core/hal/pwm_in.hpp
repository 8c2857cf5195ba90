#pragma once
#include <cstdint>

namespace rotord::hal {

/// The last complete period of a PWM signal (MA3 absolute encoder output).
struct PwmPeriod {
  std::uint32_t high_us = 0;
  std::uint32_t low_us = 0;
  /// False when no edge was seen for longer than the input's timeout
  /// (disconnected encoder).
  bool valid = false;
};

class PwmIn {
 public:
  virtual ~PwmIn() = default;
  virtual PwmPeriod read() = 0;
};

}  // namespace rotord::hal
