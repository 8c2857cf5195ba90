#include "services.hpp"

#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "web/http_session.hpp"

namespace rotord::linux_port {

std::vector<ServiceConfig> make_services(const Options& options, Controller& controller,
                                         web::Api& api, const settings::Settings& settings,
                                         metrics::Registry& registry) {
  const auto max_clients = static_cast<std::size_t>(settings.i(settings::Id::kNetMaxClients));
  std::vector<ServiceConfig> services;
  services.push_back({"web UI and REST API", static_cast<std::uint16_t>(options.web_port),
                      max_clients, std::string(web::HttpSession::kTooManyConnections),
                      [&api] { return std::make_unique<web::HttpSession>(api); }});
  services.back().protocol = metrics::Protocol::kHttp;
  services.push_back({"WRC text protocol", static_cast<std::uint16_t>(options.wrc_port),
                      max_clients, std::string(protocol::WrcSession::kTooManyConnections),
                      [&controller] {
                        return std::make_unique<protocol::WrcSession>(controller, ROTORD_VERSION);
                      }});
  services.back().protocol = metrics::Protocol::kWrc;
  // Hamlib rotctld (Gpredict, SatNOGS, rotctl -m 2): no greeting, one write per reply.
  services.push_back({"Hamlib rotctld", static_cast<std::uint16_t>(options.rotctld_port),
                      max_clients, std::string(protocol::RotctldSession::kTooManyConnections),
                      [&controller] {
                        return std::make_unique<protocol::RotctldSession>(controller,
                                                                          ROTORD_VERSION);
                      },
                      "rotctld"});
  services.back().protocol = metrics::Protocol::kRotctld;
  // Yaesu GS-232A/B; which one follows gs232.variant, read per command. The
  // real controllers and Hamlib's backends run at 9600 baud.
  services.push_back(
      {"Yaesu GS-232", static_cast<std::uint16_t>(options.gs232_port), max_clients,
       std::string(protocol::Gs232Session::kTooManyConnections),
       [&controller] { return std::make_unique<protocol::Gs232Session>(controller); }, "gs232",
       9600});
  services.back().protocol = metrics::Protocol::kGs232;
  // Hamlib's Easycomm backends default to 19200 baud.
  services.push_back({"Easycomm II/III", static_cast<std::uint16_t>(options.easycomm_port),
                      max_clients, std::string(protocol::EasycommSession::kTooManyConnections),
                      [&controller] {
                        return std::make_unique<protocol::EasycommSession>(controller,
                                                                           ROTORD_VERSION);
                      },
                      "easycomm", 19200});
  services.back().protocol = metrics::Protocol::kEasycomm;
  services.push_back({"seed $cmd protocol", static_cast<std::uint16_t>(options.seed_port),
                      max_clients, std::string(protocol::SeedSession::kTooManyConnections),
                      [&controller] { return std::make_unique<protocol::SeedSession>(controller); },
                      "seed", 9600});
  for (auto& service : services) service.settings = &settings;
  // Open pages' live streams never take the slots STOP needs.
  services.front().max_event_streams =
      static_cast<std::size_t>(settings.i(settings::Id::kWebMaxEventStreams));
  services.back().protocol = metrics::Protocol::kSeed;
  for (ServiceConfig& service : services) service.metrics = &registry;
  return services;
}

}  // namespace rotord::linux_port
