#pragma once
// The commands with typed arguments (docs/architecture.md, "The command
// layer"): what the line protocols, the console and the UDP messages call
// once they have read their own bytes, and what Commands (commands.hpp)
// calls once it has read the JSON of REST and MQTT. Each command's checks
// and its call into the controller are here once; the errors are the
// controller's own values (util/error.hpp), which every front end turns
// into its own reply bytes (a Hamlib RPRT code, GS-232's `?>`, HTTP 409).
// Each writes its one log line here too (command_log.hpp), with `from`, the
// front end and client that sent it; an empty `from.front` writes none
// (Commands, which writes the line of a REST or MQTT command itself).
//
// The manual buttons (buttons.hpp) are a front end over these too: a press
// is `move`, a release `end_jog`.
#include <optional>
#include <string_view>

#include "access/peer.hpp"
#include "command/command_log.hpp"
#include "rotator/controller.hpp"
#include "rotator/place.hpp"
#include "settings/preset.hpp"

namespace rotord::command {

/// Whether `peer` may call a command without a login (a line protocol, the
/// console, a UDP message): its network is allowed (access.control_networks,
/// or access.serial_control for a local line; failed closed while the access
/// settings are unreadable) and nobody holds the control lock (taken through
/// the web or REST only, so never by such a client). STOP never asks. Writes
/// nothing: for a status ("in control: yes").
bool in_control(const Controller& controller, const access::Peer& peer);
/// in_control() for the command `what` (the front end's own name of it,
/// "P", "set_pos"): a refusal is logged (DENIED, or LOCKED by the lock).
bool may_control(Controller& controller, const Origin& from, std::string_view what);

/// STOP: every axis, every motion; for anyone.
void stop(Controller& controller, const Origin& from);
/// Stops one axis (a line protocol's per-axis stop); kNotSupported for an
/// elevation the rotator does not have.
Error stop_axis(Controller& controller, const Origin& from, AxisId axis);
/// Go to `az_deg` and/or `el_deg`; `source` is the caller's stream for the
/// continuity rule (rotator/goto_stream.hpp).
Error go_to(Controller& controller, const Origin& from, std::optional<float> az_deg,
            std::optional<float> el_deg, AzTarget mode = AzTarget::kCompass,
            CommandSource source = kNoSource);
/// Turn an axis (Direction::kNone stops it) at `speed_pct` (-1: the
/// controller's speed).
Error move(Controller& controller, const Origin& from, AxisId axis, Direction dir,
           int speed_pct = -1);
/// Ends the jog on `axis` if it still jogs (a manual button released):
/// nothing else, so a go-to sent while the button was held goes on.
void end_jog(Controller& controller, const Origin& from, AxisId axis);
Error park(Controller& controller, const Origin& from);
/// Stop and clear latched faults; kFaulted while the emergency stop is active.
Error reset(Controller& controller, const Origin& from);
/// The speed for every move from now on, 1..100 %.
Error set_speed(Controller& controller, const Origin& from, int speed_pct);
/// Turn the beam to a place; `aim` tells where (and, when not reachable,
/// why: then kOutOfRange and nothing moves).
Error turn_to_place(Controller& controller, const Origin& from, const PlaceQuery& place,
                    PlaceAim& aim);
/// Turn the beam to the preset named `name` (found into `preset`);
/// kNotFound when there is none of that name.
Error turn_to_preset(Controller& controller, const Origin& from, std::string_view name,
                     settings::Preset& preset);

}  // namespace rotord::command
