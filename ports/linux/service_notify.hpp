#pragma once
// systemd's service protocol (sd_notify(3), libsystemd): Type=notify and
// WatchdogSec= in the unit. READY=1 once every port listens, so units
// ordered after rotord (and `systemctl start`) wait for a daemon that
// answers; WATCHDOG=1 from the control tick, so a loop that stops ticking
// is killed by systemd and restarted (Restart=on-failure), its outputs
// driven off by ExecStopPost= first; STOPPING=1 when it stops. Outside
// systemd (no $NOTIFY_SOCKET, no $WATCHDOG_USEC) nothing is sent.
#include <cstdint>

namespace rotord::linux_port {

class ServiceNotifier {
 public:
  /// Reads $WATCHDOG_USEC (and $WATCHDOG_PID) once.
  ServiceNotifier();

  /// READY=1 with a STATUS= line for `systemctl status`.
  void ready(const char* status) const;
  void stopping() const;
  /// Called from every control tick: WATCHDOG=1 once half the watchdog
  /// period has passed since the last one (systemd's advice).
  void tick(std::int64_t now_us);
  /// The watchdog period systemd asked for, 0 when none.
  std::uint64_t watchdog_us() const { return watchdog_us_; }

 private:
  std::uint64_t watchdog_us_ = 0;
  std::int64_t last_feed_us_ = 0;
  bool fed_ = false;
};

}  // namespace rotord::linux_port
