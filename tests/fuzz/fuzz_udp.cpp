// libFuzzer target: arbitrary datagrams into both UDP rotor protocols
// (N1MM+'s <N1MMRotor>, PstRotator's <PST>) on a controller with fake
// hardware, from an allowed and from a read-only sender. Crashes, sanitizer
// reports and broken invariants fail.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "fake_rotator.hpp"
#include "protocol/datagram_registry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rotord;
  using protocol::DatagramOutcome;
  testing::FakeRotator rotator;
  // The first byte picks the protocol, the sender and the rotor name rule.
  const std::uint8_t mode = size > 0 ? data[0] : 0;
  const std::string_view datagram(reinterpret_cast<const char*>(data) + (size > 0 ? 1 : 0),
                                  size > 0 ? size - 1 : 0);
  if ((mode & 4) != 0) rotator.settings.set_text(settings::Id::kN1mmRotorName, "Yagi 20");
  if ((mode & 2) != 0)
    rotator.settings.set_text(settings::Id::kAccessControlNetworks, "10.0.0.0/8");
  protocol::DatagramHandlers handlers(*rotator.controller);
  protocol::DatagramProtocol& p = handlers.get(
      (mode & 1) != 0 ? protocol::DatagramPersonality::kPst : protocol::DatagramPersonality::kN1mm);
  const access::Peer from = access::Peer::from_ipv4(0x7F000001);
  rotator.run_ms(20);
  protocol::DatagramReplies replies;
  const DatagramOutcome outcome = p.receive(datagram, from, replies);
  rotator.run_ms(1100);
  // What the protocol sends by itself afterwards goes to the sender only.
  protocol::DatagramReplies later;
  access::Peer to;
  if (p.poll(later, to) && (to.ipv4 != from.ipv4 || later.count() == 0)) std::abort();
  const RotatorStatus s = rotator.controller->status();
  // Bad input, an oversize datagram or a read-only sender never moves it.
  const bool may_move = outcome == DatagramOutcome::kDone;
  if (!may_move && (s.az.has_target || s.el.has_target)) std::abort();
  if (outcome == DatagramOutcome::kOversize &&
      datagram.size() <= protocol::DatagramProtocol::kMaxDatagramBytes)
    std::abort();
  // Targets stay inside the travel (az 0..450, el 0..180).
  if (s.az.has_target && (s.az.target_deg < 0.0f || s.az.target_deg > 450.0f)) std::abort();
  if (s.el.has_target && (s.el.target_deg < 0.0f || s.el.target_deg > 180.0f)) std::abort();
  // Never both directions of one axis at once.
  for (const auto* axis : {&rotator.az, &rotator.el}) {
    const auto& out = axis->drive.last;
    if (out.on(OutputChannel::kRelayCw) && out.on(OutputChannel::kRelayCcw)) std::abort();
  }
  // Replies are bounded, and only answers to well-formed messages.
  if (replies.count() > protocol::DatagramReplies::kMaxReplies) std::abort();
  if (replies.count() > 0 && outcome == DatagramOutcome::kMalformed) std::abort();
  return 0;
}
