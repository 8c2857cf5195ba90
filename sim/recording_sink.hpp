#pragma once
#include "axis/drive_outputs.hpp"

namespace rotord::sim {

/// The simulator's end of an axis' output wiring: it keeps the outputs the
/// controller applied last, and the plant runs on them until the next apply.
class RecordingSink final : public DriveSink {
 public:
  void apply(const DriveOutputs& outputs) override {
    last_ = outputs;
    ++apply_count_;
  }
  const DriveOutputs& last() const { return last_; }
  long apply_count() const { return apply_count_; }

 private:
  DriveOutputs last_{};  // all off at power-up
  long apply_count_ = 0;
};

}  // namespace rotord::sim
