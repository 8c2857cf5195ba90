#include "web/route_log.hpp"

#include <cmath>

#include "command/command_log.hpp"
#include "util/slice.hpp"

namespace rotord::web {

const command::Def* command_of(const Api::Route& route) {
  if (!route.post || !route.path.starts_with("/api/")) return nullptr;
  return command::Commands::find(text::slice(route.path, 5));
}

void told_refused(Controller& controller, const Api::Route& route, Method method,
                  const access::Peer& peer, std::string_view outcome) {
  std::string_view what;
  std::string_view args;
  if (const command::Def* d = command_of(route)) {
    what = d->name;
  } else if (!route.post) {
    return;  // a query writes nothing
  } else if (route.path == "/api/track") {
    what = "track";
    args = method == Method::kDelete ? "stop" : "start";
  } else if (route.path == "/api/odometer/reset") {
    what = "odometer reset";
  } else if (route.path == "/api/wind/override") {
    what = "wind";
  } else {
    return;
  }
  command::told(controller, {"rest", peer}, what, outcome, NAN, NAN, args);
}

}  // namespace rotord::web
