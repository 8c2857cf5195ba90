#pragma once
#include <cstdint>

namespace rotord::hal {

/// A counter of pulses on an input (an anemometer's reed contact): the
/// Pico W counts falling edges in a GPIO interrupt, Linux through libgpiod's
/// edge events. The count only grows (and wraps at 2^32); readers take
/// differences.
class PulseCounter {
 public:
  virtual ~PulseCounter() = default;
  virtual std::uint32_t count() = 0;
};

}  // namespace rotord::hal
