// libFuzzer target: arbitrary bytes into a SeedSession on a controller with
// fake hardware. Crashes, sanitizer reports and broken invariants fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "protocol/seed_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rotord::testing::FakeRotator rotator;
  const auto revision = rotator.settings.revision();
  rotord::protocol::SeedSession session(*rotator.controller);
  rotord::fuzz::NullSink sink;
  rotord::fuzz::feed_in_two(session, rotator, data, size, sink);
  rotord::fuzz::abort_on_both_directions(rotator);
  // Targets stay inside the travel (az 0..450, el 0..180) unless the input
  // itself changed the settings.
  if (rotator.settings.revision() == revision)
    rotord::fuzz::abort_on_target_outside_travel(rotator);
  // Every reply line is bounded, so output is bounded by the input size.
  if (sink.bytes > 256 + size * 64) std::abort();
  return 0;
}
