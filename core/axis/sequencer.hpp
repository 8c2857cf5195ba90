#pragma once
#include <array>
#include <cstdint>

#include "axis/drive_outputs.hpp"
#include "util/direction.hpp"
#include "util/time.hpp"

namespace rotord {

/// What one step of a timed sequence does. Direction-relative targets are
/// resolved against the direction the sequence runs for, so one start
/// sequence serves both directions.
enum class StepTarget : std::uint8_t {
  kDirRelay,     ///< the relay of the sequence's direction (the other one is forced off)
  kBrake,        ///< brake solenoid, 1 = released
  kSpeedFast,    ///< two-speed output
  kVoltageFast,  ///< voltage-select relay
  kDirPwm,       ///< H-bridge duty of the sequence's direction
  kAllOff,       ///< every output off
};

struct SeqStep {
  StepTarget target;
  float value;
  std::uint16_t hold_ms;  ///< time before the next step runs
};

/// A fixed-capacity list of steps: relay timing is data, not code (a soft
/// start of a 6 V creep / 48 V fast motor is a sequence, not a branch).
class Sequence {
 public:
  static constexpr int kMaxSteps = 8;

  bool add(StepTarget target, float value, int hold_ms);
  int size() const { return count_; }
  const SeqStep& operator[](int n) const { return steps_[static_cast<std::size_t>(n)]; }
  Millis total_ms() const;

 private:
  std::array<SeqStep, kMaxSteps> steps_{};
  int count_ = 0;
};

/// Plays a Sequence onto DriveOutputs in time.
class Sequencer {
 public:
  void start(const Sequence& seq, Direction dir, Millis now);
  /// Applies every step that is due; returns true while steps or holds remain.
  bool run(Millis now, DriveOutputs& out);
  bool active() const { return active_; }
  void cancel() { active_ = false; }

  static void apply(const SeqStep& step, Direction dir, DriveOutputs& out);

 private:
  Sequence seq_;
  Direction dir_ = Direction::kNone;
  int next_ = 0;
  Millis next_at_ = 0;
  bool active_ = false;
};

}  // namespace rotord
