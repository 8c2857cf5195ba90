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
  if (settings_ == nullptr || !peer.is_network()) return false;
  if (settings_->access_unreadable()) return false;  // the list itself is unknown
  // An empty list makes every client a controller (access control off), so
  // nobody is protected by it: an idle stranger must not hold a slot forever.
  const std::string_view networks = settings_->text(settings::Id::kAccessControlNetworks);
  return !networks.empty() && settings::in_network_list(networks, peer);
}

bool Admission::same_host(const ClientInfo& a, const ClientInfo& b) const {
  if (a.address == b.address) return true;
  // IPv6: a host picks any address of its /64 at will, so the /64 is the
  // host; but allow-listed addresses are the owner's own devices, which
  // share their LAN's /64 (docs/security.md, "IPv6").
  return a.peer.kind == access::Peer::Kind::kIpv6 && a.peer.same_host(b.peer) &&
         !control_listed(a.peer) && !control_listed(b.peer);
}

std::size_t Admission::idlest(const ClientList& clients, const ClientInfo* only, bool any_listed,
                              Millis now) const {
  const Millis threshold = idle_evict_ms();
  if (threshold < 0) return kNone;
  std::size_t best = kNone;
  Millis best_since = 0;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr || c->event_stream || c->stop_only) continue;
    if (only != nullptr && !same_host(*c, *only)) continue;
    if (!c->between_requests && now - c->last_useful_ms < threshold) continue;
    if (!any_listed && control_listed(c->peer)) continue;
    if (best == kNone || c->last_useful_ms < best_since) {
      best = i;
      best_since = c->last_useful_ms;
    }
  }
  return best;
}

std::size_t Admission::least_useful(const ClientList& clients, bool listed) const {
  std::size_t best = kNone;
  Millis best_since = 0;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr || c->event_stream || c->stop_only) continue;
    if (control_listed(c->peer) != listed) continue;
    // A keep-alive connection between requests has nothing in progress.
    const Millis since = c->between_requests ? -1 : c->last_useful_ms;
    if (best == kNone || since < best_since) {
      best = i;
      best_since = since;
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

Admission::Decision Admission::stop_only_or(const ClientList& clients, const ClientInfo& newcomer,
                                            Decision::Kind refusal) {
  std::size_t taken = 0;
  bool same_host = false;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr || !c->stop_only) continue;
    ++taken;
    same_host = same_host || this->same_host(*c, newcomer);
  }
  if (taken < limits_.stop_only_slots && !same_host) {
    ++counters_.stop_only;
    return {Decision::Kind::kStopOnly, kNone};
  }
  if (refusal == Decision::Kind::kRefusePerAddress) {
    ++counters_.refused_per_address;
  } else {
    ++counters_.refused_full;
  }
  return {refusal, kNone};
}

Admission::Decision Admission::admit(const ClientList& clients, const ClientInfo& newcomer,
                                     Millis now) {
  std::size_t requests = 0;
  std::size_t streams = 0;
  std::size_t same_host = 0;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    const ClientInfo* c = clients.at(i);
    if (c == nullptr || c->stop_only) continue;
    if (c->event_stream) {
      ++streams;
      continue;
    }
    ++requests;
    if (this->same_host(*c, newcomer)) ++same_host;
  }

  Decision d;
  if (same_host >= per_address_cap()) {
    d.evict = idlest(clients, &newcomer, true, now);
    if (d.evict == kNone) return stop_only_or(clients, newcomer, Decision::Kind::kRefusePerAddress);
    ++counters_.evicted_idle;
  } else if (requests >= limits_.max_clients || requests + streams >= limits_.slots) {
    // Every static slot taken but requests have room: a view gives way first.
    if (requests < limits_.max_clients && streams > 0) {
      d.evict = oldest_stream(clients, kNone);
      ++counters_.evicted_event_stream;
    } else if ((d.evict = idlest(clients, nullptr, false, now)) != kNone) {
      ++counters_.evicted_idle;
    } else if (control_listed(newcomer.peer)) {
      // The owner first: a stranger gives way, however busy; among listed
      // clients only, the one least recently useful.
      d.evict = least_useful(clients, false);
      if (d.evict == kNone) d.evict = least_useful(clients, true);
      if (d.evict == kNone) return stop_only_or(clients, newcomer, Decision::Kind::kRefuseFull);
      ++counters_.evicted_for_listed;
    } else {
      return stop_only_or(clients, newcomer, Decision::Kind::kRefuseFull);
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
