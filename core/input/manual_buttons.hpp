#pragma once
#include <array>

#include "hal/digital_in.hpp"
#include "input/debouncer.hpp"
#include "util/axis_id.hpp"
#include "util/direction.hpp"

namespace rotord {

/// Front-panel CW/CCW (and UP/DOWN) push buttons turned into manual moves:
/// debounced; held = move, released = stop; both of a pair held = stop. A
/// button must be seen released once before it counts, so a button stuck or
/// held at power-on never starts the motor. Pure logic: the controller polls
/// it from its tick and applies the commands.
class ManualButtons {
 public:
  struct Inputs {
    hal::DigitalIn* forward = nullptr;  ///< CW / UP
    hal::DigitalIn* reverse = nullptr;  ///< CCW / DOWN
  };
  /// What the buttons want an axis to do, when it changed in this poll.
  struct Command {
    bool changed = false;
    Direction dir = Direction::kNone;
  };

  ManualButtons(const Inputs& az, const Inputs& el) : inputs_{az, el} {}
  void configure(bool enabled, Millis debounce_ms);
  bool enabled() const { return enabled_; }
  /// Samples every wired button; returns one command per axis (AxisId order).
  std::array<Command, kMaxAxes> poll(Millis now);

 private:
  struct Button {
    Debouncer debounce;
    bool armed = false;
    bool update(hal::DigitalIn* in, Millis now);
  };
  struct AxisButtons {
    Button forward, reverse;
    Direction wanted = Direction::kNone;
  };

  std::array<Inputs, kMaxAxes> inputs_;
  std::array<AxisButtons, kMaxAxes> axes_{};
  bool enabled_ = false;
};

}  // namespace rotord
