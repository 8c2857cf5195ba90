#pragma once
// What the line sessions' libFuzzer targets share: a sink that only counts,
// the feeding of the input in two parts with ticks in between, and the
// invariants every session holds to whatever bytes it was sent.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "protocol/session.hpp"

namespace rotord::fuzz {

/// Counts what a session writes and keeps nothing.
struct NullSink final : protocol::ByteSink {
  std::size_t bytes = 0;
  void write(std::string_view data) override { bytes += data.size(); }
};

/// Feeds the input in two chunks split at a data-dependent point (from its
/// first byte), running the controller 50 ms after each, then polls: partial
/// lines and commands mid-move are both exercised.
inline void feed_in_two(protocol::Session& session, testing::FakeRotator& rotator,
                        const std::uint8_t* data, std::size_t size, protocol::ByteSink& sink) {
  const std::size_t split = size > 0 ? data[0] % (size + 1) : 0;
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  session.receive(all.substr(0, split), sink);
  rotator.run_ms(50);
  session.receive(all.substr(split), sink);
  rotator.run_ms(50);
  session.poll(rotator.now, sink);
}

/// Never both directions of one axis at once, whatever was sent.
inline void abort_on_both_directions(const testing::FakeRotator& rotator) {
  for (const auto* axis : {&rotator.az, &rotator.el}) {
    const auto& out = axis->drive.last;
    if (out.on(OutputChannel::kRelayCw) && out.on(OutputChannel::kRelayCcw)) std::abort();
  }
}

/// A go-to's target stays inside the fake rotator's travel (az 0..450, el
/// 0..180), whatever angles were sent.
inline void abort_on_target_outside_travel(const testing::FakeRotator& rotator) {
  const RotatorStatus s = rotator.controller->status();
  if (s.az.has_target && (s.az.target_deg < 0.0f || s.az.target_deg > 450.0f)) std::abort();
  if (s.el.has_target && (s.el.target_deg < 0.0f || s.el.target_deg > 180.0f)) std::abort();
}

/// The whole run of a session whose every reply line is bounded (Easycomm,
/// seed): the input fed in two; never both directions; a go-to's target
/// inside the travel unless the input itself changed the settings (Easycomm's
/// CW writes them); output bounded by the input size.
inline void run_bounded_line_session(protocol::Session& session, testing::FakeRotator& rotator,
                                     const std::uint8_t* data, std::size_t size) {
  const auto revision = rotator.settings.revision();
  NullSink sink;
  feed_in_two(session, rotator, data, size, sink);
  abort_on_both_directions(rotator);
  if (rotator.settings.revision() == revision) abort_on_target_outside_travel(rotator);
  if (sink.bytes > 256 + size * 64) std::abort();
}

}  // namespace rotord::fuzz
