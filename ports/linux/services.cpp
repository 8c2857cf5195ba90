#include "services.hpp"

#include "protocol/wrc_session.hpp"
#include "web/http_session.hpp"

namespace rotord::linux_port {

std::vector<ServiceConfig> make_services(const Options& options, Controller& controller,
                                         web::Api& api, std::size_t max_clients) {
  std::vector<ServiceConfig> services;
  services.push_back({"web UI and REST API", static_cast<std::uint16_t>(options.web_port),
                      max_clients, std::string(web::HttpSession::kTooManyConnections),
                      [&api] { return std::make_unique<web::HttpSession>(api); }});
  services.push_back({"WRC text protocol", static_cast<std::uint16_t>(options.wrc_port),
                      max_clients, std::string(protocol::WrcSession::kTooManyConnections),
                      [&controller] {
                        return std::make_unique<protocol::WrcSession>(controller, ROTORD_VERSION);
                      }});
  return services;
}

}  // namespace rotord::linux_port
