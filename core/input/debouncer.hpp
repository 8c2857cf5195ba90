#pragma once
#include "util/time.hpp"

namespace rotord {

/// Debounces one contact in time: the state changes only after the raw input
/// has held its new level for `stable_ms` without a bounce. Polled from the
/// control tick (10 ms); no interrupts, no heap.
class Debouncer {
 public:
  Debouncer() = default;
  explicit Debouncer(Millis stable_ms) : stable_ms_(stable_ms) {}
  void set_stable_ms(Millis stable_ms) { stable_ms_ = stable_ms; }

  /// Feeds one raw sample taken at `now`; returns the debounced state.
  bool update(bool raw, Millis now);
  bool state() const { return state_; }
  /// The input has held one level for stable_ms since the first sample (a
  /// button held down at power-on is settled and active).
  bool settled() const { return settled_; }
  /// The last update() changed the state to active / inactive.
  bool pressed() const { return pressed_; }
  bool released() const { return released_; }

 private:
  Millis stable_ms_ = 30;
  bool started_ = false;
  bool settled_ = false;
  bool state_ = false;
  bool candidate_ = false;
  Millis candidate_since_ = 0;
  bool pressed_ = false;
  bool released_ = false;
};

}  // namespace rotord
