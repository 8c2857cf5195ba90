#pragma once
// The rotator as WRC's STATE shows it (the unwrapped azimuth and the motion
// flags), for interop tests that drive it through another protocol.
#include <string>

#include "daemon_process.hpp"

namespace rotord::testing {

/// One STATE on a connection of its own.
inline std::string wrc_state(const DaemonProcess& daemon) {
  TcpClient c(daemon.ports().wrc);
  return c.ask("STATE\n");
}

/// The number of `key` (e.g. "AZ") in STATE, or -1e9 when it has none.
inline double wrc_field(const DaemonProcess& daemon, const std::string& key) {
  const std::string s = wrc_state(daemon);
  const auto pos = s.find(" " + key + "=");
  return pos == std::string::npos ? -1e9 : std::stod(s.substr(pos + key.size() + 2));
}

/// Advances controller time (500 ms a step, at most 150 s) until no axis
/// moves ("CW" also finds CCW); false when one still does.
inline bool wait_until_still(DaemonProcess& daemon) {
  for (int n = 0; n < 300; ++n) {
    const std::string s = wrc_state(daemon);
    if (s.find("CW") == std::string::npos && s.find("UP") == std::string::npos &&
        s.find("DOWN") == std::string::npos)
      return true;
    daemon.advance_ms(500);
  }
  return false;
}

}  // namespace rotord::testing
