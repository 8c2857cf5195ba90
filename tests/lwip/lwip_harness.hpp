#pragma once
// Running Debian's lwIP in a test process: its tcpip thread is started once
// (lwIP cannot be de-initialised), and raw-API calls hold the core lock, the
// one-context rule the Pico's poll loop gives.
#include <atomic>
#include <chrono>
#include <thread>

extern "C" {
#include "lwip/netif.h"
#include "lwip/tcpip.h"
}

namespace rotord::testing {

inline void ensure_lwip() {
  static std::atomic<bool> ready{false};
  static bool started = false;
  if (!started) {
    started = true;
    tcpip_init([](void*) { ready = true; }, nullptr);
  }
  while (!ready) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

class CoreLock {
 public:
  CoreLock() { LOCK_TCPIP_CORE(); }
  ~CoreLock() { UNLOCK_TCPIP_CORE(); }
  CoreLock(const CoreLock&) = delete;
  CoreLock& operator=(const CoreLock&) = delete;
};

/// A test host: `n` up at `address`/24 with no gateway, its frames handled by
/// `init` (which decides what "the wire" is). Hold the CoreLock. False when
/// lwIP refuses the netif.
[[nodiscard]] inline bool add_host_netif(netif& n, const ip4_addr_t& address, netif_init_fn init) {
  ip4_addr_t mask;
  ip4_addr_t gw;
  IP4_ADDR(&mask, 255, 255, 255, 0);
  IP4_ADDR(&gw, 0, 0, 0, 0);
  if (netif_add(&n, &address, &mask, &gw, nullptr, init, tcpip_input) == nullptr) return false;
  netif_set_up(&n);
  netif_set_link_up(&n);
  return true;
}

}  // namespace rotord::testing
