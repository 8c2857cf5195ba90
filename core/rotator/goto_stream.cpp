#include "rotator/goto_stream.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord {

GotoStream::Step GotoStream::judge(float az_deg, CommandSource source, Millis now,
                                   float travel_deg) const {
  Step step;
  if (source == kNoSource || source != source_ || now - last_ms_ > kMaxGapMs) return step;
  const float d = wrap_180(az_deg - last_az_);
  const float max_step = std::fmin(kMaxStepDeg, 0.25f * travel_deg);
  if (std::fabs(d) > max_step) return step;  // a jump: a new stream
  step.same_stream = true;
  // Steps below the clients' two decimals do not say a direction.
  step.sign = d > 0.005f ? 1 : (d < -0.005f ? -1 : 0);
  const bool reversal = step.sign != 0 && dir_ != 0 && step.sign != dir_;
  step.zigzag = reversal && run_ < kSteadySteps;
  const bool literal = step.zigzag || (literal_ && !(run_ + 1 >= kSteadySteps && !reversal));
  // A client that sends unwrapped azimuths (420) chooses its turns itself.
  const bool compass = !unwrapped_ && az_deg >= 0.0f && az_deg <= 360.0f;
  step.continues = !literal && compass && gotos_ >= kMinGotos;
  return step;
}

void GotoStream::accept(const Step& step, float az_deg, float target_deg, CommandSource source,
                        Millis now) {
  if (!step.same_stream) {
    // The first go-to of a stream.
    dir_ = 0;
    run_ = 0;
    gotos_ = 0;
    literal_ = false;
    unwrapped_ = false;
  } else if (step.sign != 0 && dir_ != 0 && step.sign != dir_) {
    run_ = 1;
    if (step.zigzag) literal_ = true;
  } else {
    ++run_;
    if (run_ >= kSteadySteps) literal_ = false;
  }
  if (step.sign != 0) dir_ = step.sign;
  ++gotos_;
  if (az_deg < 0.0f || az_deg > 360.0f) unwrapped_ = true;
  source_ = source;
  last_ms_ = now;
  last_az_ = az_deg;
  last_target_ = target_deg;
}

}  // namespace rotord
