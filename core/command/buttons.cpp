#include "command/buttons.hpp"

#include "command/typed.hpp"

namespace rotord::command {

using settings::Id;

namespace {
/// A hand on the box: no client.
const Origin kOrigin{"buttons", {}};
}  // namespace

Buttons::Buttons(Controller& controller, const AxisIo& az_io, const AxisIo& el_io)
    : controller_(controller),
      buttons_({az_io.button_fwd, az_io.button_rev}, {el_io.button_fwd, el_io.button_rev}) {
  configure();
}

void Buttons::configure() {
  const settings::Settings& s = controller_.settings();
  buttons_.configure(s.b(Id::kButtonsEnabled), s.i(Id::kButtonsDebounceMs));
  applied_revision_ = s.revision();
}

void Buttons::poll(Millis now) {
  if (controller_.settings().revision() != applied_revision_) configure();
  const auto commands = buttons_.poll(now);
  for (const AxisId axis : {AxisId::kAz, AxisId::kEl}) {
    const auto n = static_cast<std::size_t>(axis_index(axis));
    if (!commands[n].changed) continue;
    if (commands[n].dir != Direction::kNone) {
      // Refused moves (fault, limit, no elevation) simply do nothing; the
      // status already shows why.
      jogging_[n] = move(controller_, kOrigin, axis, commands[n].dir) == Error::kOk;
      continue;
    }
    // Released: end the jog the button started; a go-to a client sent
    // since is left alone (end_jog ends a jog only).
    if (jogging_[n]) end_jog(controller_, kOrigin, axis);
    jogging_[n] = false;
  }
}

}  // namespace rotord::command
