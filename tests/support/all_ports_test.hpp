#pragma once
// A test fixture for the tests that press on every port of the real daemon
// at once (interop availability, line_attackers): `rotord --sim g5500
// --clock manual` with the seed protocol's port open too (off by default).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"

namespace rotord::testing {

class AllPortsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    seed_port = free_port();
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "g5500", "--clock", "manual", "--seed-port", std::to_string(seed_port)});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    web = daemon->ports().web;
  }
  /// Settings through REST, from 127.0.0.1.
  void set(const std::string& json) {
    const HttpResponse r = http(web, "POST", "/api/settings", json);
    ASSERT_EQ(r.status, 200) << r.body;
  }

  std::unique_ptr<DaemonProcess> daemon;
  int web = 0;
  int seed_port = 0;
};

/// 127.0.0.n: another host, as the per-address limits and the allow-list see it.
inline std::string host(int n) {
  return "127.0.0." + std::to_string(n);
}

}  // namespace rotord::testing
