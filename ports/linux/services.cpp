#include "services.hpp"

#include "protocol/protocol_registry.hpp"
#include "web/http_session.hpp"
#include "web/http_stop_only_session.hpp"

namespace rotord::linux_port {

std::vector<ServiceConfig> make_services(const Options& options, Controller& controller,
                                         web::Api& api, const settings::Settings& settings,
                                         metrics::Registry& registry,
                                         const protocol::ConsolePort* console) {
  const auto max_clients = static_cast<std::size_t>(settings.i(settings::Id::kNetMaxClients));
  std::vector<ServiceConfig> services;
  services.push_back({"web UI and REST API", static_cast<std::uint16_t>(options.web_port),
                      max_clients, std::string(web::HttpSession::kTooManyConnections),
                      [&api] { return std::make_unique<web::HttpSession>(api); }});
  services.back().protocol = metrics::Protocol::kHttp;
  // Over capacity, the same small session as the Pico W's (a few hundred
  // bytes, not 10 KB of request buffers): only POST /api/stop is obeyed.
  services.back().make_stop_only_session = [&api] {
    return std::make_unique<web::HttpStopOnlySession>(api);
  };
  // Open pages' live streams never take the slots STOP needs.
  services.back().max_event_streams =
      static_cast<std::size_t>(settings.i(settings::Id::kWebMaxEventStreams));
  // Every line protocol of the registry, on TCP and (by its key) on --pty
  // and --serial.
  const protocol::SessionDeps deps{controller, ROTORD_VERSION, nullptr, console};
  for (const protocol::ProtocolInfo& p : protocol::protocols()) {
    ServiceConfig service;
    service.name = std::string(p.name);
    service.port =
        static_cast<std::uint16_t>(options.line_ports[static_cast<std::size_t>(p.personality)]);
    service.max_clients = max_clients;
    service.reject_message = std::string(p.refusal);
    service.make_session = [deps, personality = p.personality] {
      return protocol::with_session_type(personality, [&deps](auto session) {
        using S = typename decltype(session)::type;
        return std::unique_ptr<protocol::Session>(new S(decltype(session)::make(deps)));
      });
    };
    service.key = std::string(p.key);
    service.serial_baud = p.serial_baud;
    service.protocol = p.metric();
    services.push_back(std::move(service));
  }
  for (ServiceConfig& service : services) {
    service.settings = &settings;
    service.metrics = &registry;
  }
  return services;
}

}  // namespace rotord::linux_port
