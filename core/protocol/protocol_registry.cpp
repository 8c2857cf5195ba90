#include "protocol/protocol_registry.hpp"

#include <array>

#include "settings/choices_table.hpp"

namespace rotord::protocol {
namespace {

using rows::kProtocols;

constexpr std::size_t txt_rows() {
  std::size_t n = 0;
  for (const ProtocolInfo& p : kProtocols) n += p.dns_sd == DnsSd::kTxt ? 1 : 0;
  return n;
}
// A row announced in the TXT record needs its room there (net/dns_sd.hpp).
static_assert(txt_rows() <= net::ServicePorts::kMaxOthers, "raise ServicePorts::kMaxOthers");

// usb.personality's choices (settings_table.def) stay a list of the
// settings layer, below this one: its table cannot include the registry, so
// they cannot be derived from the rows without a layer looking up (their
// order is their own too: the web form's, and the default's index; the
// file stores the key). They are checked against the rows here instead, at
// compile time, in every build of the core (Linux, the embedded preset, the
// Pico W): each choice but off is a row's key (usb_personality.cpp finds
// the row by it), so a renamed key cannot leave the USB port silent.
static_assert(offers_off_and_rows(settings::choices_of(settings::Id::kUsbPersonality)),
              "usb.personality's choices in settings_table.def must be off and protocol rows' "
              "keys (core/protocol/protocol_registry.hpp)");

}  // namespace

std::span<const ProtocolInfo> protocols() {
  return kProtocols;
}

const ProtocolInfo& protocol_info(Personality personality) {
  return kProtocols[static_cast<std::size_t>(personality)];
}

const ProtocolInfo* find_protocol(std::string_view key) {
  for (const ProtocolInfo& p : kProtocols) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

const ProtocolInfo* find_protocol(metrics::Protocol metric) {
  for (const ProtocolInfo& p : kProtocols) {
    if (p.metric() == metric) return &p;
  }
  return nullptr;
}

}  // namespace rotord::protocol
