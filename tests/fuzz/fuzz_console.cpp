// libFuzzer target: arbitrary bytes into a ConsoleSession (the rotord
// console, docs/protocols/console.md) on a controller with fake hardware, its
// long listings paced in data-dependent windows as the Pico's USB paces them.
// Crashes, sanitizer reports and broken invariants fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "fuzz_session.hpp"
#include "protocol/console_session.hpp"

namespace {

using rotord::fuzz::NullSink;

struct NoReboot final : rotord::command::SystemHooks {
  const char* reboot() override { return nullptr; }
  const char* reboot_to_bootloader() override { return "not here"; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rotord::testing::FakeRotator rotator;
  rotord::settings::Settings defaults = rotator.settings;
  rotord::settings::Settings scratch;
  NoReboot hooks;
  const rotord::protocol::ConsolePort port{&defaults, &scratch, &hooks, "fuzz"};
  rotord::protocol::ConsoleSession session(*rotator.controller, "fuzz", &port);
  session.set_peer(rotord::access::Peer::line());
  NullSink sink;
  const std::size_t split = size > 0 ? data[0] % (size + 1) : 0;
  const std::size_t room = size > 1 ? 1 + data[1] * 16u : 4096;
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  for (const std::string_view part : {all.substr(0, split), all.substr(split)}) {
    session.receive(part, sink);
    // A listing goes out in windows; every one makes progress.
    for (int n = 0; session.output_pending(); ++n) {
      if (n > 100000) std::abort();
      session.write_more(room, sink);
    }
    rotator.run_ms(50);
  }
  rotord::fuzz::abort_on_both_directions(rotator);
  // The console moves nothing by itself: it has no go-to.
  if (rotator.controller->status().az.has_target || rotator.controller->status().el.has_target)
    std::abort();
  // Every command's reply is bounded (a listing of every setting is the
  // longest, about 5 KB per 5 bytes of input).
  if (sink.bytes > 8192 + size * 1200) std::abort();
  return 0;
}
