#include "settings/network_list.hpp"

#include "settings/settings.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::settings {
namespace {

bool is_label(std::string_view label) {
  if (label.empty() || label.size() > 63 || label.front() == '-' || label.back() == '-')
    return false;
  for (char c : label) {
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

bool parse_ipv4_network(std::string_view text, Ipv4Network& out) {
  const std::size_t slash = text.find('/');
  std::uint32_t address = 0;
  if (!parse_ipv4(text::slice(text, 0, slash), address)) return false;
  long prefix = 32;
  if (slash != std::string_view::npos) {
    const std::string_view bits = text::slice(text, slash + 1);
    if (bits.empty() || bits.size() > 2 || !text::parse_int(bits, prefix)) return false;
    if (prefix < 0 || prefix > 32) return false;
  }
  out.mask = prefix == 0 ? 0u : ~0u << (32 - prefix);
  out.address = address & out.mask;
  return true;
}

bool parse_ipv6(std::string_view text, access::IpBytes& out) {
  // The groups before "::" and after it, then put together.
  std::uint16_t head[8] = {};
  std::uint16_t tail[8] = {};
  std::size_t heads = 0;
  std::size_t tails = 0;
  bool gap = false;
  if (text.size() < 2 || text.size() > 45) return false;
  if (text.substr(0, 2) == "::") {
    gap = true;
    text.remove_prefix(2);
  } else if (text.front() == ':') {
    return false;
  }
  while (!text.empty()) {
    std::uint16_t* groups = gap ? tail : head;
    std::size_t& count = gap ? tails : heads;
    if (heads + tails >= 8) return false;
    // An embedded IPv4 address ends the text and takes two groups.
    const std::size_t colon = text.find(':');
    const std::string_view group = text::slice(text, 0, colon);
    if (colon == std::string_view::npos && group.find('.') != std::string_view::npos) {
      std::uint32_t v4 = 0;
      if (heads + tails > 6 || !parse_ipv4(group, v4)) return false;
      groups[count++] = static_cast<std::uint16_t>(v4 >> 16);
      groups[count++] = static_cast<std::uint16_t>(v4 & 0xFFFF);
      text = {};
      break;
    }
    if (group.empty() || group.size() > 4) return false;
    unsigned value = 0;
    for (char c : group) {
      unsigned digit = 0;
      if (c >= '0' && c <= '9') {
        digit = static_cast<unsigned>(c - '0');
      } else if (c >= 'a' && c <= 'f') {
        digit = static_cast<unsigned>(c - 'a' + 10);
      } else if (c >= 'A' && c <= 'F') {
        digit = static_cast<unsigned>(c - 'A' + 10);
      } else {
        return false;
      }
      value = value * 16 + digit;
    }
    groups[count++] = static_cast<std::uint16_t>(value);
    if (colon == std::string_view::npos) break;
    text.remove_prefix(colon + 1);
    if (!text.empty() && text.front() == ':') {
      if (gap) return false;  // a second "::"
      gap = true;
      text.remove_prefix(1);
    } else if (text.empty()) {
      return false;  // a trailing single ':'
    }
  }
  // "::" stands for at least one zero group.
  if (gap ? heads + tails > 7 : heads != 8) return false;
  std::uint16_t all[8] = {};
  for (std::size_t i = 0; i < heads; ++i) all[i] = head[i];
  for (std::size_t i = 0; i < tails; ++i) all[8 - tails + i] = tail[i];
  for (std::size_t i = 0; i < 8; ++i) {
    out[2 * i] = static_cast<std::uint8_t>(all[i] >> 8);
    out[2 * i + 1] = static_cast<std::uint8_t>(all[i] & 0xFF);
  }
  return true;
}

bool IpNetwork::contains(const access::IpBytes& a) const {
  unsigned bits = prefix_bits;
  for (std::size_t i = 0; i < a.size() && bits > 0; ++i) {
    const unsigned take = bits < 8 ? bits : 8;
    const auto mask = static_cast<std::uint8_t>(0xFF00u >> take);
    if ((a[i] & mask) != (address[i] & mask)) return false;
    bits -= take;
  }
  return true;
}

bool parse_network(std::string_view text, IpNetwork& out) {
  Ipv4Network v4;
  if (parse_ipv4_network(text, v4)) {
    out.address = access::Peer::from_ipv4(v4.address).address();
    unsigned bits = 0;
    for (std::uint32_t m = v4.mask; m != 0; m <<= 1) ++bits;
    out.prefix_bits = 96 + bits;
    return true;
  }
  const std::size_t slash = text.find('/');
  access::IpBytes address{};
  if (!parse_ipv6(text::slice(text, 0, slash), address)) return false;
  long prefix = 128;
  if (slash != std::string_view::npos) {
    const std::string_view bits = text::slice(text, slash + 1);
    if (bits.empty() || bits.size() > 3 || !text::parse_int(bits, prefix)) return false;
    if (prefix < 0 || prefix > 128) return false;
  }
  out.address = address;
  out.prefix_bits = static_cast<unsigned>(prefix);
  return true;
}

bool in_network_list(std::string_view list, std::uint32_t ipv4) {
  return in_network_list(list, access::Peer::from_ipv4(ipv4));
}

bool in_network_list(std::string_view list, const access::Peer& peer) {
  if (!peer.is_network()) return false;
  const access::IpBytes address = peer.address();
  bool found = false;
  for_each_list_item(list, [&](std::string_view item) {
    IpNetwork network;
    if (!found && parse_network(item, network) && network.contains(address)) found = true;
  });
  return found;
}

bool is_hostname(std::string_view name) {
  if (name.empty() || name.size() > 253) return false;
  for (;;) {
    const std::size_t dot = name.find('.');
    if (!is_label(text::slice(name, 0, dot))) return false;
    if (dot == std::string_view::npos) return true;
    name.remove_prefix(dot + 1);
  }
}

}  // namespace rotord::settings
