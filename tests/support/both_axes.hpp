#pragma once
// Both axes of the simulated az/el rotator as the web API shows them, for
// the tests that count how often an owner's STOP gets through attackers
// (interop line_attackers, ipv6).
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "daemon_process.hpp"
#include "http_client.hpp"

namespace rotord::testing {

/// Both axes without a target: nothing moves or will.
inline bool both_axes_stopped(int web_port) {
  const std::string s = http(web_port, "GET", "/api/status").body;
  std::size_t n = 0;
  for (auto at = s.find("\"target_deg\":null"); at != std::string::npos;
       at = s.find("\"target_deg\":null", at + 1))
    ++n;
  return n == 2;
}

/// Through the web (not attacked): both axes get a target, another one each
/// round so that every round moves, and still have it 100 ms later.
inline void start_moving_both_axes(DaemonProcess& daemon, int web_port, int round) {
  const HttpResponse r =
      http(web_port, "POST", "/api/goto",
           round % 2 == 0 ? R"({"az": 300, "el": 40})" : R"({"az": 100, "el": 20})");
  ASSERT_EQ(r.status, 200) << r.body;
  daemon.advance_ms(100);
  ASSERT_FALSE(both_axes_stopped(web_port));
}

}  // namespace rotord::testing
