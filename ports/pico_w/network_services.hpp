#pragma once
// Everything the Pico W has and the plain Pico has not: the Wi-Fi chip, lwIP
// with every line protocol on TCP, the web UI and REST API, mDNS, SNTP, web
// access control (mbedtls) and the TLEs tracking needs (with SNTP's time).
// Compiled only into the Pico W image (ROTORD_PICO_NETWORK, CMakeLists.txt);
// main.cpp calls it from the same one loop as the control tick.
#include "command/system_commands.hpp"
#include "hal/storage.hpp"
#include "metrics/registry.hpp"
#include "pico/time.h"
#include "protocol/protocol_registry.hpp"
#include "rotator/controller.hpp"
#include "settings/settings.hpp"
#include "util/byte_sink.hpp"
#include "util/time.hpp"

namespace rotord::web {
class LoadReport;
}

namespace rotord::pico_w {

/// What the network services take from the rest of the firmware.
struct NetworkDeps {
  Controller& controller;
  settings::Settings& settings;
  const settings::Settings* defaults;  ///< for the web's reset
  hal::Storage* storage;               ///< the settings saver; nullptr: RAM only
  metrics::Registry& registry;
  /// The USB log port, for output that matters only as it happens (WRC
  /// MONITOR lines, the web's log).
  protocol::ByteSink& log;
  /// POST /api/reboot, the same restart as the console's `reboot`: the
  /// loop reboots once the answer is out.
  command::SystemHooks* system;
  /// What reading the settings flash dropped (GET /api/status "settings_load").
  const web::LoadReport* load_report = nullptr;
};

/// Starts the Wi-Fi chip (blocking: its firmware load), then Wi-Fi and every
/// server. Without the chip the controller still runs: the log says why the
/// network is down and the other calls below do only what needs no network.
void network_start(const NetworkDeps& deps, Millis now);
/// Every loop pass: lwIP and the Wi-Fi driver.
void network_service();
/// Every control tick, after the controller's.
void network_tick(Millis now);
/// Until `next_tick`: a login's hash slices, then sleep until the Wi-Fi
/// chip has work or the tick is due.
void network_wait_until(absolute_time_t next_tick);

}  // namespace rotord::pico_w
