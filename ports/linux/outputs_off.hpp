#pragma once
// `rotord --outputs-off`: every output the settings wire, driven off by a
// process of its own, for systemd's ExecStopPost= after any exit of the
// daemon (kill -9 and the watchdog's SIGABRT included), when the kernel has
// left each GPIO line at its last value and each PWM channel running. Relay,
// speed and brake lines are requested as outputs, inactive (the
// gpiod.outputs_active_low polarity applied, so an active-low board gets a
// high level), then released: the line keeps the inactive level. H-bridge
// PWM channels get duty 0 and are disabled. Each output on its own, so one
// that fails does not keep the others on.
#include <functional>
#include <memory>
#include <string>

#include "gpio_line.hpp"
#include "options.hpp"
#include "settings/settings.hpp"

namespace rotord::linux_port {

struct OutputsOffResult {
  int lines_off = 0;     ///< GPIO lines requested inactive and released
  int channels_off = 0;  ///< PWM channels at duty 0 and disabled
  std::string done;      ///< "az.cw line 17, ..." for the log
  std::string errors;    ///< one sentence per output that could not be driven off
  bool ok() const { return errors.empty(); }
};

/// Opens the GPIO chip (called only when some line is wired).
using OpenChip = std::function<std::unique_ptr<GpioChip>(std::string& error)>;

/// Drives off the outputs of the azimuth, and of the elevation when
/// el.enabled, as `GpiodRotator::open` would have requested them.
OutputsOffResult drive_outputs_off(const settings::Settings& s, const OpenChip& open_chip,
                                   const std::string& pwm_root);

/// The command: reads the settings as the daemon would (options.hpp's
/// --config, --hw), drives the outputs off on the machine's GPIO chip and
/// PWM sysfs, logs what it did. Exit code 0 (also under --hw sim: nothing to
/// drive), 1 when an output could not be driven off, 2 when the settings
/// file cannot be used.
int run_outputs_off(const Options& options);

}  // namespace rotord::linux_port
