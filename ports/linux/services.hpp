#pragma once
#include <vector>

#include "options.hpp"
#include "rotator/controller.hpp"
#include "tcp_server.hpp"
#include "web/web_api.hpp"

namespace rotord::linux_port {

/// Every protocol the daemon serves on TCP, with its port from the options.
/// A port of 0 leaves that service out. Connection limits come from
/// `settings` (net.max_clients, web.max_event_streams at start-up; the
/// admission rule reads the rest at each newcomer). Each counts its
/// connections and error replies in `registry` under its protocol. The
/// console's sessions get `console` (reboot, import's working copy).
std::vector<ServiceConfig> make_services(const Options& options, Controller& controller,
                                         web::Api& api, const settings::Settings& settings,
                                         metrics::Registry& registry,
                                         const protocol::ConsolePort* console = nullptr);

}  // namespace rotord::linux_port
