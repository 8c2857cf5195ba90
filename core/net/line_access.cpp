#include "net/line_access.hpp"

#include "settings/network_list.hpp"

namespace rotord::access {

bool may_control(const settings::Settings& settings, const Peer& peer) {
  // Failed closed: the rules that would say who may are unknown.
  if (settings.access_unreadable()) return false;
  switch (peer.kind) {
    case Peer::Kind::kUnknown:
      return true;
    case Peer::Kind::kLine:
      return settings.b(settings::Id::kAccessLineControl);
    case Peer::Kind::kIpv4:
    case Peer::Kind::kIpv6:
    case Peer::Kind::kOther: {
      const std::string_view networks = settings.text(settings::Id::kAccessControlNetworks);
      if (networks.empty()) return true;
      return settings::in_network_list(networks, peer);
    }
  }
  return false;
}

}  // namespace rotord::access
