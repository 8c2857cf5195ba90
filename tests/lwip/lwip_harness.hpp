#pragma once
// Running Debian's lwIP in a test process: its tcpip thread is started once
// (lwIP cannot be de-initialised), and raw-API calls hold the core lock, the
// one-context rule the Pico's poll loop gives.
#include <atomic>
#include <chrono>
#include <thread>

extern "C" {
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

}  // namespace rotord::testing
