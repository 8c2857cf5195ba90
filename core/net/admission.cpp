#include "net/admission.hpp"

#include <algorithm>

#include "settings/network_list.hpp"
#include "settings/settings.hpp"

namespace rotord::net {

Address Address::from_ipv4(std::uint32_t host_order) {
  Address a;
  a.bytes[10] = 0xFF;
  a.bytes[11] = 0xFF;
  a.bytes[12] = static_cast<std::uint8_t>(host_order >> 24);
  a.bytes[13] = static_cast<std::uint8_t>(host_order >> 16);
  a.bytes[14] = static_cast<std::uint8_t>(host_order >> 8);
  a.bytes[15] = static_cast<std::uint8_t>(host_order);
  return a;
}

Address Address::from_ipv6(const std::uint8_t (&network_order)[16]) {
  Address a;
  std::copy(std::begin(network_order), std::end(network_order), a.bytes.begin());
  return a;
}

std::size_t Admission::per_address_cap() const {
  if (settings_ == nullptr) return SIZE_MAX;
  const auto setting = static_cast<std::size_t>(settings_->i(settings::Id::kNetMaxPerAddress));
  // Below max_clients, so one host never takes every slot whatever is set.
  const std::size_t below_limit = limits_.max_clients > 1 ? limits_.max_clients - 1 : 1;
  return std::clamp<std::size_t>(setting, 1, below_limit);
}

Millis Admission::idle_evict_ms() const {
  if (settings_ == nullptr) return -1;
  return static_cast<Millis>(settings_->i(settings::Id::kNetIdleEvictS)) * 1000;
}

bool Admission::control_listed(const access::Peer& peer) const {
  if (settings_ == nullptr || peer.kind != access::Peer::Kind::kIpv4) return false;
  // An empty list makes every client a controller (access control off), so
  // nobody is protected by it: an idle stranger must not hold a slot forever.
  const std::string_view networks = settings_->text(settings::Id::kAccessControlNetworks);
  return !networks.empty() && settings::in_network_list(networks, peer.ipv4);
}

std::size_t Admission::idlest(const ClientList& clients, const Address* only, bool any_listed,
                              Millis now) const {
  const Millis threshold = idle_evict_ms();
  if (threshold < 0) return kNone;
  std::size_t best = kNone;
  Millis best_since = 0;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr || c->event_stream) continue;
    if (only != nullptr && !(c->address == *only)) continue;
    if (!c->between_requests && now - c->last_receive_ms < threshold) continue;
    if (!any_listed && control_listed(c->peer)) continue;
    if (best == kNone || c->last_receive_ms < best_since) {
      best = i;
      best_since = c->last_receive_ms;
    }
  }
  return best;
}

std::size_t Admission::oldest_stream(const ClientList& clients, std::size_t except) const {
  std::size_t best = kNone;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr || !c->event_stream || i == except) continue;
    if (best == kNone || c->opened_ms < clients.at(best)->opened_ms) best = i;
  }
  return best;
}

Admission::Decision Admission::admit(const ClientList& clients, const ClientInfo& newcomer,
                                     Millis now) {
  std::size_t requests = 0;
  std::size_t streams = 0;
  std::size_t same_host = 0;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr) continue;
    if (c->event_stream) {
      ++streams;
      continue;
    }
    ++requests;
    if (c->address == newcomer.address) ++same_host;
  }

  Decision d;
  if (same_host >= per_address_cap()) {
    d.evict = idlest(clients, &newcomer.address, true, now);
    if (d.evict == kNone) {
      ++counters_.refused_per_address;
      return {Decision::Kind::kRefusePerAddress, kNone};
    }
    ++counters_.evicted_idle;
  } else if (requests >= limits_.max_clients || requests + streams >= limits_.slots) {
    // Every static slot taken but requests have room: a view gives way first.
    if (requests < limits_.max_clients && streams > 0) {
      d.evict = oldest_stream(clients, kNone);
      ++counters_.evicted_event_stream;
    } else {
      d.evict = idlest(clients, nullptr, false, now);
      if (d.evict == kNone) {
        ++counters_.refused_full;
        return {Decision::Kind::kRefuseFull, kNone};
      }
      ++counters_.evicted_idle;
    }
  }
  ++counters_.accepted;
  return d;
}

std::size_t Admission::stream_started(const ClientList& clients, std::size_t self) {
  std::size_t streams = 0;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c != nullptr && c->event_stream) ++streams;
  }
  if (streams <= limits_.max_event_streams) return kNone;
  const std::size_t victim = oldest_stream(clients, self);
  if (victim != kNone) ++counters_.evicted_event_stream;
  return victim;
}

}  // namespace rotord::net
