#pragma once
#include <chrono>

#include "hal/wall_clock.hpp"

namespace rotord::linux_port {

/// The host's system clock (kept by the host's NTP client) as the API's
/// calendar time; rotord does no SNTP of its own on Linux.
class SystemWallClock final : public hal::WallClock {
 public:
  std::optional<std::int64_t> unix_ms() const override {
    using namespace std::chrono;
    return duration_cast<milliseconds>(system_clock::now().time_since_epoch()).count();
  }
};

}  // namespace rotord::linux_port
