#pragma once
// Restarting the controller (docs/logging.md): REST's POST /api/reboot and
// the console's `reboot` and `bootsel` are these two commands, each with
// its log line ("command reboot from rest (192.168.1.30): OK"), whichever
// front end took them. The front end passes its gate first (the REST route
// table's control rule, the console's may_control()).
#include "command/command_log.hpp"
#include "rotator/controller.hpp"

namespace rotord::command {

/// What only a port can do: restart the controller (Linux: re-create it in
/// process; the Pico W: a watchdog reset), and restart into the ROM's USB
/// bootloader. Each is asked while a request is being handled, so the port
/// acts later, after the reply has gone out; each returns nullptr when it
/// will happen, or why it cannot (the console's error text).
class SystemHooks {
 public:
  virtual ~SystemHooks() = default;
  virtual const char* reboot() = 0;
  virtual const char* reboot_to_bootloader() = 0;
};

/// A restart's outcome: kOk (it will happen), or kNotSupported and why.
struct Restart {
  Error error = Error::kOk;
  const char* why = nullptr;  ///< the console's words; nullptr when kOk
  bool ok() const { return error == Error::kOk; }
};

/// Restarts the controller through `hooks` (nullptr: the port cannot).
/// Logged "reboot": OK or NOT SUPPORTED.
Restart reboot(Controller& controller, const Origin& from, SystemHooks* hooks);
/// Restarts into the USB bootloader, for a firmware update. Logged
/// "bootsel": OK or NOT SUPPORTED (rotord on Linux has no bootloader).
Restart reboot_to_bootloader(Controller& controller, const Origin& from, SystemHooks* hooks);

}  // namespace rotord::command
