#include "sntp_clock.hpp"

namespace rotord::pico_w {
namespace {

// One calendar time per device, written only from lwIP's context (the poll
// loop), read from the same loop: no locking needed.
TimeBase g_time_base;
std::uint32_t g_updates = 0;

}  // namespace

void on_sntp_time(std::uint32_t sec, std::uint32_t us, Millis now) {
  g_time_base.set(unix_ms_from_sntp(sec, us), now);
  ++g_updates;
}

std::optional<std::int64_t> SntpWallClock::unix_ms() const {
  return g_time_base.unix_ms(now_());
}

std::uint32_t sntp_updates() {
  return g_updates;
}

}  // namespace rotord::pico_w
