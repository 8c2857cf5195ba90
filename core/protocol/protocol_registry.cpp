#include "protocol/protocol_registry.hpp"

#include <array>

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
