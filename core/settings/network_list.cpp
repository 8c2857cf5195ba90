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

bool in_network_list(std::string_view list, std::uint32_t ipv4) {
  bool found = false;
  for_each_list_item(list, [&](std::string_view item) {
    Ipv4Network network;
    if (!found && parse_ipv4_network(item, network) && network.contains(ipv4)) found = true;
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
