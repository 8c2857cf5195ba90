#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "rotator/controller.hpp"

namespace rotord {

/// What the log should say about the axes since it last asked: a fault
/// latched (named: a frozen sensor, a burst, a stall, a slip), a slip
/// (counted and published whether or not slip.fault is on), a re-hold after
/// it (slip.rehold) or its limit reached, a go-to held by
/// the starts ceiling (care.max_starts_h: its tolerance widened), the wind
/// stow beginning and ending, wind readings ignored. The ports ask
/// from their main loop, never from the control tick. No heap.
class AxisEvents {
 public:
  /// Takes the counts as they are now: only later events are told.
  void begin(const RotatorStatus& status);
  /// Writes the next event into `line` (NUL-terminated), or returns false
  /// when there is none. Call until false.
  bool next(const RotatorStatus& status, char* line, std::size_t capacity);

 private:
  std::array<std::uint32_t, 2> slips_{};
  std::array<std::uint32_t, 2> reholds_{};
  std::array<std::uint32_t, 2> reholds_refused_{};
  std::array<AxisFault, 2> faults_{};
  std::array<bool, 2> held_{};
  /// The wind stow's (docs/care.md): its state, and the rejected readings
  /// told at 1, 10, 100, ... (garbage at MQTT rates must not flood the log).
  bool wind_event(const RotatorStatus& status, char* line, std::size_t capacity);
  care::WindState wind_state_ = care::WindState::kOff;
  std::uint32_t wind_rejected_ = 0;
  std::uint32_t wind_rejected_told_at_ = 1;
};

}  // namespace rotord
