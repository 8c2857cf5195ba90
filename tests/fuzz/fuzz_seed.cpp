// libFuzzer target: arbitrary bytes into a SeedSession on a controller with
// fake hardware. Crashes, sanitizer reports and broken invariants fail.
#include <cstddef>
#include <cstdint>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "protocol/seed_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rotord::testing::FakeRotator rotator;
  rotord::protocol::SeedSession session(*rotator.controller);
  rotord::fuzz::run_bounded_line_session(session, rotator, data, size);
  return 0;
}
