#include "web/host_check.hpp"

#include <cstring>

#include "settings/network_list.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::web {
namespace {

bool is_port(std::string_view text) {
  if (text.empty() || text.size() > 5) return false;
  for (char c : text)
    if (c < '0' || c > '9') return false;
  return true;
}

/// An IPv6 literal between brackets, as a Host carries it: hex digits,
/// colons, dots (an embedded IPv4) and nothing else.
bool is_ipv6_literal(std::string_view inside) {
  if (inside.size() < 2 || inside.find(':') == std::string_view::npos) return false;
  for (char c : inside) {
    const bool ok = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F') ||
                    c == ':' || c == '.';
    if (!ok) return false;
  }
  return true;
}

/// `name` or `name.local`, case-insensitively.
bool is_name_or_mdns(std::string_view host, std::string_view name) {
  if (name.empty()) return false;
  if (text::iequals(host, name)) return true;
  return host.size() == name.size() + 6 && text::iequals(text::slice(host, 0, name.size()), name) &&
         text::iequals(text::slice(host, name.size()), ".local");
}

bool in_allowed_hosts(std::string_view name, const settings::Settings& settings) {
  bool found = false;
  settings::for_each_list_item(settings.text(settings::Id::kWebAllowedHosts),
                               [&](std::string_view allowed) {
                                 if (text::iequals(allowed, name)) found = true;
                               });
  return found;
}

/// The host name of an authority (host[:port]); false when it is malformed.
/// An IPv6 literal comes back with its brackets.
bool host_of(std::string_view authority, std::string_view& name) {
  if (!authority.empty() && authority.front() == '[') {
    const std::size_t close = authority.find(']');
    if (close == std::string_view::npos) return false;
    const std::string_view after = text::slice(authority, close + 1);
    if (!after.empty() && (after.front() != ':' || !is_port(text::slice(after, 1)))) return false;
    name = text::slice(authority, 0, close + 1);
    return is_ipv6_literal(text::slice(name, 1, name.size() - 2));
  }
  const std::size_t colon = authority.rfind(':');
  if (colon != std::string_view::npos && !is_port(text::slice(authority, colon + 1))) return false;
  name = text::slice(authority, 0, colon);
  if (!name.empty() && name.back() == '.') name.remove_suffix(1);  // "rotord.local."
  return !name.empty();
}

}  // namespace

bool host_allowed(std::string_view host, const settings::Settings& settings,
                  const char* system_hostname) {
  if (host.empty()) return true;
  std::string_view name;
  if (!host_of(host, name)) return false;
  if (name.front() == '[') return true;  // an address cannot be rebound
  std::uint32_t ignored = 0;
  if (settings::parse_ipv4(name, ignored)) return true;
  if (text::iequals(name, "localhost")) return true;
  if (is_name_or_mdns(name, settings.text(settings::Id::kNetHostname))) return true;
  if (system_hostname != nullptr) {
    const std::string_view system(system_hostname);
    if (is_name_or_mdns(name, system)) return true;
    // A host named "pi.example.org" is also found as "pi" and "pi.local".
    if (is_name_or_mdns(name, text::slice(system, 0, system.find('.')))) return true;
  }
  return in_allowed_hosts(name, settings);
}

bool origin_allowed(std::string_view origin, std::string_view host,
                    const settings::Settings& settings) {
  if (origin.empty()) return true;
  const std::size_t scheme_end = origin.find("://");
  if (scheme_end == std::string_view::npos) return false;  // "null" and anything odd
  const std::string_view authority = text::slice(origin, scheme_end + 3);
  if (authority.empty() || authority.find('/') != std::string_view::npos) return false;
  if (!host.empty() && text::iequals(authority, host)) return true;
  std::string_view name;
  return host_of(authority, name) && in_allowed_hosts(name, settings);
}

}  // namespace rotord::web
