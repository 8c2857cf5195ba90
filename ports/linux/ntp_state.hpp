#pragma once
#include <sys/timex.h>

#include <cstddef>

#include "hal/clock_sync.hpp"

namespace rotord::linux_port {

/// What the kernel says of the system clock (adjtimex, as timedatectl's
/// "System clock synchronized" and "NTP service"), in the owner's words.
struct NtpReading {
  int state = 0;           ///< adjtimex's return: TIME_OK..TIME_ERROR, or -1
  int error = 0;           ///< errno when state is -1
  long status = 0;         ///< timex.status (STA_UNSYNC...)
  long esterror_us = 0;    ///< estimated error
  long maxerror_us = 0;    ///< maximum error
  bool timesyncd = false;  ///< systemd-timesyncd says it is synchronized
};

/// The words for one reading (pure, for the tests).
std::size_t describe_ntp(const NtpReading& r, char* out, std::size_t capacity);

/// The host's NTP state, read at each call: rotord does no NTP of its own on
/// Linux, the host's client (systemd-timesyncd, chrony, ntpd) keeps the
/// clock.
class NtpState final : public hal::ClockSync {
 public:
  std::size_t describe(char* out, std::size_t capacity) const override;
};

}  // namespace rotord::linux_port
