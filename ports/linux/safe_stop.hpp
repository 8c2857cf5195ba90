#pragma once
// What every way out of rotord does before the process ends (a signal, a
// failed controller restart, the end of the loop): the motors stop through
// the same path a STOP command takes, then every output is written off in
// the core and, under --hw gpiod, at the lines once more.
#include <string>

#include "axis/drive_outputs.hpp"
#include "gpiod_io.hpp"
#include "rotator/controller.hpp"

namespace rotord::linux_port {

/// Controller::stop() (requests cleared, mode idle, as a STOP command does),
/// Controller::shutdown() (all outputs off now, through each axis's drive
/// sink: the simulator's plant or the gpiod lines), then GpiodRotator::all_off()
/// (every mapped line written inactive whatever it held). Either may be null.
void stop_motors(Controller* controller, GpiodRotator* gpio);

/// "az off, el off", or the channels still on ("az relay_cw=1 brake=1, el
/// off"), from the outputs the driver last wrote.
std::string describe_outputs(const DriveOutputs& az, const DriveOutputs* el);

}  // namespace rotord::linux_port
