// libFuzzer target: arbitrary bytes into a rotctld session on a controller
// with fake hardware. Crashes, sanitizer reports and broken invariants fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "protocol/rotctld_session.hpp"

namespace {

struct CheckingSink final : rotord::protocol::ByteSink {
  std::size_t bytes = 0;
  void write(std::string_view data) override {
    // Every reply is one non-empty write of at most one reply buffer, and
    // every reply ends its last record with LF (RPRT lines, values, ERP).
    if (data.empty() || data.size() > rotord::protocol::rotctld::ReplyBuffer::kCapacity ||
        data.back() != '\n')
      std::abort();
    bytes += data.size();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rotord::testing::FakeRotator rotator;
  rotord::protocol::RotctldSession session(*rotator.controller, "fuzz");
  CheckingSink sink;
  // Feed in chunks split at a data-dependent point, ticking in between, so
  // partial commands, commands mid-move and the end of a \pause are exercised.
  const std::size_t split = size > 0 ? data[0] % (size + 1) : 0;
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  session.receive(all.substr(0, split), sink);
  rotator.run_ms(50);
  session.poll(rotator.now, sink);
  session.receive(all.substr(split), sink);
  rotator.run_ms(2000);
  session.poll(rotator.now, sink);
  rotord::fuzz::abort_on_both_directions(rotator);
  // At most one reply per input byte.
  if (sink.bytes > (size + 1) * rotord::protocol::rotctld::ReplyBuffer::kCapacity) std::abort();
  return 0;
}
