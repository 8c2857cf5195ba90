#include "web/route_log.hpp"

#include <cmath>

#include "command/command_log.hpp"
#include "util/slice.hpp"

namespace rotord::web {
namespace {

/// The command layer's words for a route outside its table: its success
/// line's (care_commands.hpp, settings_commands.hpp, commission_commands.hpp)
/// up to what the refusal leaves unread (a preset's key: its settings row).
struct RouteWords {
  const char* path;
  const char* what;
};
constexpr RouteWords kRouteWords[] = {
    {"/api/track", "track"},  // start, or DELETE: stop
    {"/api/odometer/reset", "odometer reset"},
    {"/api/wind/override", "wind"},
    {"/api/tle", "tle"},  // DELETE: tle delete
    {"/api/settings", "set"},
    {"/api/presets", "set"},
    {"/api/presets/delete", "set"},
    {"/api/settings/reset", "reset settings"},
    {"/api/setup/model", "setup model"},
    {"/api/commission", "commission"},
    {"/api/commission/accept", "commission accept"},
    {"/api/reboot", "reboot"},
};

}  // namespace

const command::Def* command_of(const Api::Route& route) {
  if (!route.post || !route.path.starts_with("/api/")) return nullptr;
  return command::Commands::find(text::slice(route.path, 5));
}

void told_refused(Controller& controller, const Api::Route& route, Method method,
                  const access::Peer& peer, std::string_view outcome) {
  const command::Origin from{"rest", peer};
  if (const command::Def* d = command_of(route)) {
    command::told(controller, from, d->name, outcome);
    return;
  }
  if (!route.post) return;  // a query writes nothing
  const bool del = method == Method::kDelete;
  for (const RouteWords& w : kRouteWords)
    if (route.path == w.path)
      return command::told(controller, from, w.what, outcome, NAN, NAN,
                           w.path == kRouteWords[0].path ? (del ? "stop" : "start")
                           : del                         ? "delete"
                                                         : "");
}

}  // namespace rotord::web
