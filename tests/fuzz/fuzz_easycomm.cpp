// libFuzzer target: arbitrary bytes into a EasycommSession on a controller with
// fake hardware. Crashes, sanitizer reports and broken invariants fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "protocol/easycomm_session.hpp"

namespace {

struct NullSink final : rotord::protocol::ByteSink {
  std::size_t bytes = 0;
  void write(std::string_view data) override { bytes += data.size(); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rotord::testing::FakeRotator rotator;
  const auto revision = rotator.settings.revision();
  rotord::protocol::EasycommSession session(*rotator.controller, "fuzz");
  NullSink sink;
  // Feed in chunks split at a data-dependent point, ticking in between, so
  // partial lines and commands mid-move are both exercised.
  const std::size_t split = size > 0 ? data[0] % (size + 1) : 0;
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  session.receive(all.substr(0, split), sink);
  rotator.run_ms(50);
  session.receive(all.substr(split), sink);
  rotator.run_ms(50);
  session.poll(rotator.now, sink);
  // Never both directions of one axis at once, whatever was sent.
  for (const auto* axis : {&rotator.az, &rotator.el}) {
    const auto& out = axis->drive.last;
    if (out.on(rotord::OutputChannel::kRelayCw) && out.on(rotord::OutputChannel::kRelayCcw))
      std::abort();
  }
  // Targets stay inside the travel (az 0..450, el 0..180) unless the input
  // itself changed the limits (Easycomm CW writes settings).
  const rotord::RotatorStatus s = rotator.controller->status();
  if (rotator.settings.revision() != revision) return 0;
  if (s.az.has_target && (s.az.target_deg < 0.0f || s.az.target_deg > 450.0f)) std::abort();
  if (s.el.has_target && (s.el.target_deg < 0.0f || s.el.target_deg > 180.0f)) std::abort();
  // Every reply line is bounded, so output is bounded by the input size.
  if (sink.bytes > 256 + size * 64) std::abort();
  return 0;
}
