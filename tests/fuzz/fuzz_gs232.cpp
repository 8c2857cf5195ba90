// libFuzzer target: arbitrary bytes into a GS-232 session (A or B, chosen by
// the first byte) on a controller with fake hardware. Crashes, sanitizer
// reports and broken invariants fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "protocol/gs232_session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using rotord::settings::Id;
  rotord::testing::FakeRotator rotator;
  const std::uint8_t mode = size > 0 ? data[0] : 0;
  rotator.settings.set(Id::kGs232Variant, mode & 1);
  rotator.settings.set(Id::kGs232AckWrites, (mode >> 1) & 1);
  rotator.settings.set(Id::kGs232AzRange, (mode >> 2) % 3);
  rotord::protocol::Gs232Session session(*rotator.controller);
  rotord::fuzz::NullSink sink;
  // Feed in chunks split at a data-dependent point, ticking in between, so
  // partial lines, commands mid-move and timed-list steps are all exercised.
  const std::size_t split = size > 1 ? data[1] % (size + 1) : 0;
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  session.receive(all.substr(0, split), sink);
  for (int n = 0; n < 5; ++n) {
    rotator.run_ms(400);
    session.poll(rotator.now, sink);
  }
  session.receive(all.substr(split), sink);
  for (int n = 0; n < 5; ++n) {
    rotator.run_ms(400);
    session.poll(rotator.now, sink);
  }
  rotord::fuzz::abort_on_both_directions(rotator);
  // No GS-232 command changes the travel, so targets stay inside it (az
  // 0..450, el 0..180) whatever angles were sent.
  rotord::fuzz::abort_on_target_outside_travel(rotator);
  if (session.list_size() > rotord::protocol::Gs232Session::kMaxListPoints) std::abort();
  // Replies are bounded per command (the longest is a help page, ~600 bytes
  // for "H" and a line end), so output is bounded by the input size.
  if (sink.bytes > 256 + size * 400) std::abort();
  return 0;
}
