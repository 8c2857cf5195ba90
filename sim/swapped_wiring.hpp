#pragma once
#include "axis/drive_outputs.hpp"

namespace rotord::sim {

/// The relay (or H-bridge) wires swapped at the hardware boundary: what the
/// controller calls CW turns the rotator CCW. Self-commissioning must find it.
class SwappedWiring : public DriveSink {
 public:
  explicit SwappedWiring(DriveSink* to) : to_(to) {}
  bool swapped = false;
  void apply(const DriveOutputs& in) override {
    DriveOutputs out = in;
    if (swapped) {
      out.set(OutputChannel::kRelayCw, in.get(OutputChannel::kRelayCcw));
      out.set(OutputChannel::kRelayCcw, in.get(OutputChannel::kRelayCw));
      out.set(OutputChannel::kPwmCw, in.get(OutputChannel::kPwmCcw));
      out.set(OutputChannel::kPwmCcw, in.get(OutputChannel::kPwmCw));
    }
    to_->apply(out);
  }

 private:
  DriveSink* to_;
};

}  // namespace rotord::sim
