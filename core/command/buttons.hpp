#pragma once
// The manual push buttons at the rotator (buttons.enabled) as a front end
// of the command layer, like the line protocols and REST: a press is the
// typed command `move`, a release `end_jog` (typed.hpp). The port polls
// them once a loop, just before Controller::tick, where the controller
// polled them itself before the command layer: same order, same commands.
//
// No access rule applies: a hand on the box is at the rotator, not on a
// network (no allow-list, and the control lock, taken through the web, does
// not hold it back); the controller refuses a press as it refuses any move
// (latched fault, limit, wind stow, no elevation), which the status shows.
#include <array>
#include <cstdint>

#include "axis/axis_io.hpp"
#include "input/manual_buttons.hpp"
#include "rotator/controller.hpp"

namespace rotord::command {

class Buttons {
 public:
  /// The buttons wired on each axis (AxisIo::button_fwd, button_rev; null
  /// when not fitted).
  Buttons(Controller& controller, const AxisIo& az_io, const AxisIo& el_io);
  /// Samples every wired button and turns a change into a command; call
  /// before Controller::tick(now). No heap: the control tick's rules hold.
  void poll(Millis now);

 private:
  /// buttons.enabled and buttons.debounce_ms, read again after a change.
  void configure();

  Controller& controller_;
  ManualButtons buttons_;
  std::array<bool, kMaxAxes> jogging_{};  // the jog on this axis came from a button
  std::uint32_t applied_revision_ = 0;
};

}  // namespace rotord::command
