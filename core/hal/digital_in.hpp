#pragma once

namespace rotord::hal {

/// A digital input already corrected for polarity: true means "active"
/// (switch closed, threshold reached).
class DigitalIn {
 public:
  virtual ~DigitalIn() = default;
  virtual bool active() = 0;
};

}  // namespace rotord::hal
