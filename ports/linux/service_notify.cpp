#include "service_notify.hpp"

#include <systemd/sd-daemon.h>

#include <string>

namespace rotord::linux_port {

ServiceNotifier::ServiceNotifier() {
  std::uint64_t usec = 0;
  // > 0 only when $WATCHDOG_USEC is set and $WATCHDOG_PID, if set, is us.
  if (sd_watchdog_enabled(0, &usec) > 0) watchdog_us_ = usec;
}

void ServiceNotifier::ready(const char* status) const {
  // A no-op without $NOTIFY_SOCKET; an error (the socket gone) changes nothing here.
  sd_notify(0, (std::string("READY=1\nSTATUS=") + status).c_str());
}

void ServiceNotifier::stopping() const {
  sd_notify(0, "STOPPING=1\nSTATUS=stopping the motors");
}

void ServiceNotifier::tick(std::int64_t now_us) {
  if (watchdog_us_ == 0) return;
  if (fed_ && now_us - last_feed_us_ < static_cast<std::int64_t>(watchdog_us_ / 2)) return;
  sd_notify(0, "WATCHDOG=1");
  last_feed_us_ = now_us;
  fed_ = true;
}

}  // namespace rotord::linux_port
