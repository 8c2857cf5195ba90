// The one wall-clock wait of the C++ interop tests: a bounded poll that ends
// as soon as its condition holds.
//
// Use it only where what is waited for runs on the wall clock and no daemon
// clock can move it: another process getting ready (socat, an HTTP server),
// a download, the broker's delivery, the daemon's reboot timer, --speedup.
// Everything on the network's or the controller's clock is advanced instead
// (DaemonProcess::advance_ms under --clock manual). The bound is for
// liveness only, wide for a loaded 2-core machine; nothing is ever timed.
#pragma once

#include <chrono>
#include <thread>

namespace rotord::testing {

/// Calls `condition()` until it returns true or `bound` of wall time has
/// passed, sleeping `interval` (at most, 100 ms by default) between calls.
/// Returns the last result: false only when the bound ran out.
template <typename Condition>
bool poll_until(Condition condition, std::chrono::milliseconds bound,
                std::chrono::milliseconds interval = std::chrono::milliseconds(100)) {
  const auto end = std::chrono::steady_clock::now() + bound;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(interval);  // wall time: see the comment at the top
  }
  return true;
}

}  // namespace rotord::testing
