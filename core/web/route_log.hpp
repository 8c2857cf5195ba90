#pragma once
// The log line of a REST route refused at its gate, before its command ran
// (command/command_log.hpp): in the command layer's words for it, so a
// refused POST /api/goto reads as a refused rotctld `P`, and a refused
// POST /api/odometer/reset as the console's refused `odometer reset`, and
// a refused POST /api/settings as the console's refused `set`.
#include <string_view>

#include "web/web_api.hpp"

namespace rotord::web {

/// The command of the command table a route runs (POST /api/goto: goto),
/// or nullptr.
const command::Def* command_of(const Api::Route& route);
/// Logs `outcome` ("DENIED", "LOCKED") from `peer` for a refused route that
/// runs a command: the table's (goto, ...), the tracking mode's (POST and
/// DELETE /api/track: track start, track stop; PUT and DELETE /api/tle: tle,
/// tle delete), the odometer's reset, the wind override's (wind), the
/// settings writes' (set: the settings and the presets; reset settings,
/// setup model, commission, commission accept). Other routes write nothing.
void told_refused(Controller& controller, const Api::Route& route, Method method,
                  const access::Peer& peer, std::string_view outcome);

}  // namespace rotord::web
