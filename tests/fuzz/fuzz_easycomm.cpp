// libFuzzer target: arbitrary bytes into a EasycommSession on a controller with
// fake hardware. Crashes, sanitizer reports and broken invariants fail.
#include <cstddef>
#include <cstdint>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "protocol/easycomm_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rotord::testing::FakeRotator rotator;
  rotord::protocol::EasycommSession session(*rotator.controller, "fuzz");
  rotord::fuzz::run_bounded_line_session(session, rotator, data, size);
  return 0;
}
