#include "ntp_state.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "host_path.hpp"

namespace rotord::linux_port {

std::size_t describe_ntp(const NtpReading& r, char* out, std::size_t capacity) {
  int n = 0;
  if (r.state == -1) {
    n = std::snprintf(out, capacity,
                      "The kernel does not say whether the system clock is synchronized "
                      "(adjtimex: %s).",
                      std::strerror(r.error));
  } else if (r.state != TIME_ERROR && (r.status & STA_UNSYNC) == 0) {
    n = std::snprintf(out, capacity,
                      "The system clock is synchronized by NTP%s: estimated error %.1f ms, at "
                      "most %.0f ms.",
                      r.timesyncd ? " (systemd-timesyncd)" : "",
                      static_cast<double>(r.esterror_us) / 1000.0,
                      static_cast<double>(r.maxerror_us) / 1000.0);
  } else {
    n = std::snprintf(out, capacity,
                      "The system clock is not synchronized: no NTP client keeps it. Turn one "
                      "on (sudo timedatectl set-ntp true, or install chrony); tracking waits "
                      "for it unless time.trust_system_clock is on.");
  }
  if (n < 0) return 0;
  return static_cast<std::size_t>(n) < capacity ? static_cast<std::size_t>(n) : capacity - 1;
}

std::size_t NtpState::describe(char* out, std::size_t capacity) const {
  NtpReading r;
  struct timex tx {};
  r.state = ::adjtimex(&tx);
  r.error = errno;
  r.status = tx.status;
  r.esterror_us = tx.esterror;
  r.maxerror_us = tx.maxerror;
  // systemd-timesyncd creates this file once it has synchronized the clock
  // (systemd 239 and later); ROTORD_TIMESYNC_FILE points tests elsewhere.
  const std::string synced =
      host_path("ROTORD_TIMESYNC_FILE", "/run/systemd/timesync/synchronized");
  r.timesyncd = ::access(synced.c_str(), F_OK) == 0;
  return describe_ntp(r, out, capacity);
}

}  // namespace rotord::linux_port
