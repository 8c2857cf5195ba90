#include "sntp_clock.hpp"

#include <cstdio>
#include <cstring>

namespace rotord::pico_w {
namespace {

// One calendar time per device, written only from lwIP's context (the poll
// loop), read from the same loop: no locking needed.
TimeBase g_time_base;
std::uint32_t g_updates = 0;
Millis g_last_update_ms = 0;

}  // namespace

void on_sntp_time(std::uint32_t sec, std::uint32_t us, Millis now) {
  g_time_base.set(unix_ms_from_sntp(sec, us), now);
  ++g_updates;
  g_last_update_ms = now;
}

std::optional<std::int64_t> SntpWallClock::unix_ms() const {
  return g_time_base.unix_ms(now_());
}

std::uint32_t sntp_updates() {
  return g_updates;
}

SntpState::SntpState(NowFn now, bool enabled, std::string_view server)
    : now_(now), enabled_(enabled && !server.empty()) {
  const std::size_t n = server.size() < sizeof server_ - 1 ? server.size() : sizeof server_ - 1;
  std::memcpy(server_, server.data(), n);
}

std::size_t SntpState::describe(char* out, std::size_t capacity) const {
  int n = 0;
  if (!enabled_) {
    n = std::snprintf(out, capacity,
                      "SNTP is off (time.sntp_enabled): the clock is not set, and tracking is "
                      "refused.");
  } else if (g_updates == 0) {
    n = std::snprintf(out, capacity,
                      "Waiting for the first answer of the SNTP server %s (once the Wi-Fi is "
                      "up): tracking waits for it.",
                      server_);
  } else {
    const unsigned long ago_s = static_cast<unsigned long>((now_() - g_last_update_ms) / 1000);
    n = std::snprintf(out, capacity, "Set by SNTP from %s %lu s ago (%lu answers).", server_, ago_s,
                      static_cast<unsigned long>(g_updates));
  }
  if (n < 0 || capacity == 0) return 0;
  return static_cast<std::size_t>(n) < capacity ? static_cast<std::size_t>(n) : capacity - 1;
}

}  // namespace rotord::pico_w
