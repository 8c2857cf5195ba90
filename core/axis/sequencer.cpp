#include "axis/sequencer.hpp"

namespace rotord {

bool Sequence::add(StepTarget target, float value, int hold_ms) {
  if (count_ >= kMaxSteps) return false;
  if (hold_ms < 0) hold_ms = 0;
  if (hold_ms > 65535) hold_ms = 65535;
  steps_[static_cast<std::size_t>(count_++)] = {target, value, static_cast<std::uint16_t>(hold_ms)};
  return true;
}

Millis Sequence::total_ms() const {
  Millis total = 0;
  for (int n = 0; n < count_; ++n) total += steps_[static_cast<std::size_t>(n)].hold_ms;
  return total;
}

void Sequencer::start(const Sequence& seq, Direction dir, Millis now) {
  seq_ = seq;
  dir_ = dir;
  next_ = 0;
  next_at_ = now;
  active_ = true;
}

bool Sequencer::run(Millis now, DriveOutputs& out) {
  while (active_ && now >= next_at_) {
    if (next_ >= seq_.size()) {
      active_ = false;
      break;
    }
    const SeqStep& step = seq_[next_++];
    apply(step, dir_, out);
    next_at_ += step.hold_ms;
  }
  return active_;
}

void Sequencer::apply(const SeqStep& step, Direction dir, DriveOutputs& out) {
  const bool cw = dir == Direction::kCw;
  switch (step.target) {
    case StepTarget::kDirRelay:
      out.set(cw ? OutputChannel::kRelayCcw : OutputChannel::kRelayCw, 0.0f);
      out.set(cw ? OutputChannel::kRelayCw : OutputChannel::kRelayCcw, step.value);
      break;
    case StepTarget::kBrake:
      out.set(OutputChannel::kBrake, step.value);
      break;
    case StepTarget::kSpeedFast:
      out.set(OutputChannel::kSpeedFast, step.value);
      break;
    case StepTarget::kVoltageFast:
      out.set(OutputChannel::kVoltageFast, step.value);
      break;
    case StepTarget::kDirPwm:
      out.set(cw ? OutputChannel::kPwmCcw : OutputChannel::kPwmCw, 0.0f);
      out.set(cw ? OutputChannel::kPwmCw : OutputChannel::kPwmCcw, step.value);
      break;
    case StepTarget::kAllOff:
      out.all_off();
      break;
  }
}

}  // namespace rotord
