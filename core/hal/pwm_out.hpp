#pragma once

namespace rotord::hal {

/// A PWM output; duty in 0..1.
class PwmOut {
 public:
  virtual ~PwmOut() = default;
  virtual void set_duty(float duty) = 0;
};

}  // namespace rotord::hal
