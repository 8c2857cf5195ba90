#pragma once
// The web's defence against DNS rebinding and cross-site requests: a page
// from another site may make the operator's browser send requests to the
// controller, but the browser names that site in Host (after rebinding) or
// in Origin, which these checks refuse.
#include <string_view>

#include "settings/settings.hpp"

namespace rotord::web {

/// Whether a request's Host names this device: an IP literal, localhost,
/// net.hostname (and <name>.local), the host's own name `system_hostname`
/// (Linux; null on the Pico) and <name>.local, or a web.allowed_hosts entry.
/// No Host at all (an HTTP/1.0 tool, never a browser) passes.
bool host_allowed(std::string_view host, const settings::Settings& settings,
                  const char* system_hostname);

/// Whether a state-changing request may come from `origin`: none (curl,
/// scripts; browsers always send one with fetch and forms), the page's own
/// origin (its authority is the Host), or a web.allowed_hosts name. "null"
/// (a sandboxed frame, a file) never passes.
bool origin_allowed(std::string_view origin, std::string_view host,
                    const settings::Settings& settings);

}  // namespace rotord::web
