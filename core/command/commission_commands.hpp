#pragma once
// Set-up and self-commissioning in the command layer (docs/commissioning.md):
// REST (web/setup_api.cpp) and the console (protocol/console_setup.cpp)
// call these once they have read their bytes; each writes its one log line
// (docs/logging.md):
//   command commission az all from console (USB): OK
//   command commission accept from rest (192.168.1.20): OK
//   command setup model from rest (192.168.1.20): OK
//   command setup station from console (USB): OK
// The changes they make to the settings end as a settings write does
// (settings_commands.hpp): saved through a Store when REST asks, else by the
// port's settings saver.
#include "command/settings_commands.hpp"
#include "settings/rotator_models.hpp"

namespace rotord::command {

/// Starts self-commissioning (a step, or all) of request.axis; `why` tells a
/// refusal (kBusy: a run is on; kFaulted: a fault; else the request's).
Error commission(Controller& controller, const Origin& from, const Commissioning::Request& request,
                 const char** why);
/// Writes the finished run's proposal; kInvalid with the reason when there
/// is none (or it breaks a rule): nothing changed.
SetResult accept_commissioning(Controller& controller, const Origin& from, const Store* store);
/// Fills the settings from a model's published figures; kInvalid with the
/// reason when they break a rule: nothing changed.
SetResult apply_model(Controller& controller, const Origin& from,
                      const settings::RotatorModel& model, const Store* store);
/// The station's position, both or neither; kInvalid with the reason.
SetResult set_station(Controller& controller, const Origin& from, double lat_deg, double lon_deg);

}  // namespace rotord::command
