#pragma once

namespace rotord::hal {

/// A digital output (relay, enable line); true means energised.
class DigitalOut {
 public:
  virtual ~DigitalOut() = default;
  virtual void write(bool energised) = 0;
};

}  // namespace rotord::hal
