#include "command/system_commands.hpp"

namespace rotord::command {
namespace {

/// Both restarts in one body: the M0+'s flash is tight.
Restart restart(Controller& controller, const Origin& from, SystemHooks* hooks, bool bootloader) {
  const char* why = nullptr;
  if (hooks == nullptr) {
    why = bootloader ? "bootsel is not available on this port"
                     : "reboot is not available on this port";
  } else {
    why = bootloader ? hooks->reboot_to_bootloader() : hooks->reboot();
  }
  const Restart r{why == nullptr ? Error::kOk : Error::kNotSupported, why};
  told(controller, from, bootloader ? "bootsel" : "reboot", r.error);
  return r;
}

}  // namespace

Restart reboot(Controller& controller, const Origin& from, SystemHooks* hooks) {
  return restart(controller, from, hooks, false);
}

Restart reboot_to_bootloader(Controller& controller, const Origin& from, SystemHooks* hooks) {
  return restart(controller, from, hooks, true);
}

}  // namespace rotord::command
