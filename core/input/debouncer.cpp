#include "input/debouncer.hpp"

namespace rotord {

bool Debouncer::update(bool raw, Millis now) {
  pressed_ = released_ = false;
  if (!started_ || raw != candidate_) {
    started_ = true;
    candidate_ = raw;
    candidate_since_ = now;
  }
  const bool stable = now - candidate_since_ >= stable_ms_;
  if (stable) settled_ = true;
  if (candidate_ != state_ && stable) {
    state_ = candidate_;
    pressed_ = state_;
    released_ = !state_;
  }
  return state_;
}

}  // namespace rotord
