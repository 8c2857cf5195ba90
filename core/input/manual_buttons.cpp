#include "input/manual_buttons.hpp"

namespace rotord {

void ManualButtons::configure(bool enabled, Millis debounce_ms) {
  enabled_ = enabled;
  for (auto& a : axes_) {
    a.forward.debounce.set_stable_ms(debounce_ms);
    a.reverse.debounce.set_stable_ms(debounce_ms);
  }
}

bool ManualButtons::Button::update(hal::DigitalIn* in, Millis now) {
  if (in == nullptr) return false;
  const bool down = debounce.update(in->active(), now);
  if (debounce.settled() && !down) armed = true;
  return armed && down;
}

std::array<ManualButtons::Command, kMaxAxes> ManualButtons::poll(Millis now) {
  std::array<Command, kMaxAxes> out{};
  for (std::size_t n = 0; n < axes_.size(); ++n) {
    AxisButtons& a = axes_[n];
    // Sampled even while disabled, so the debounced state is current the
    // moment the buttons are enabled.
    const bool forward = a.forward.update(inputs_[n].forward, now);
    const bool reverse = a.reverse.update(inputs_[n].reverse, now);
    Direction want = Direction::kNone;
    if (enabled_ && forward != reverse) want = forward ? Direction::kCw : Direction::kCcw;
    if (want != a.wanted) {
      a.wanted = want;
      out[n] = {true, want};
    }
  }
  return out;
}

}  // namespace rotord
