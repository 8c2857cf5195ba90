#pragma once
// The commands of the tracking mode and of the care of an unattended
// rotator (docs/architecture.md, "The command layer"; docs/tracking.md,
// docs/care.md): start and end a track, reset the wear odometer, override
// the wind stow and end the override, store TLEs. Each exists here once, with its call
// into the controller and its log line (command_log.hpp), for every front
// end: REST (web/track_api.cpp, web/tle_api.cpp, web/care_api.cpp, web/wind_api.cpp) and the
// console (protocol/console_care.cpp). As with typed.hpp, the front end
// passes its gate first (the REST route table's, or may_control() for the
// console), and reads its own bytes into these typed arguments.
#include "command/command_log.hpp"
#include "command/result.hpp"
#include "rotator/controller.hpp"
#include "tracking/tle_catalog.hpp"

namespace rotord::command {

/// Arms the tracking mode (Controller::track): logged "track start <name>"
/// (the object's name, sun, moon, or the az/el asked).
TrackError track(Controller& controller, const Origin& from, const TrackRequest& request);
/// How a refused track is answered: kConflict for what may pass (no clock,
/// no station, a fault, the wind stow, below the horizon now), else
/// kUnprocessable.
Status track_refusal(TrackError e);
/// Ends the track: the rotator stops where it is (as STOP). "track stop".
void end_track(Controller& controller, const Origin& from);

/// Stores the TLEs of a paste (tracking::TleCatalog::put, all or nothing;
/// `check` says what it came to), then saves them through `storage` when
/// the port keeps them (`document`: the saved text's work space). "tle <n>
/// objects" (n: the sets taken); kInvalidArgument (a set refused), kBusy
/// (more objects than the store holds), kStorage (stored in RAM, not saved).
Error put_tles(Controller& controller, const Origin& from, tracking::TleCatalog& tles,
               std::string_view text, hal::Storage* storage, std::span<char> document,
               tracking::TleCheck& check);

/// Removes a stored object (`object`: its name or catalog number), saved
/// as put_tles saves: "tle delete <object>"; kNotFound (none such), kStorage.
Error delete_tle(Controller& controller, const Origin& from, tracking::TleCatalog& tles,
                 const char* object, hal::Storage* storage, std::span<char> document);

/// Resets the wear odometer, dated with UTC when known (0 when not); the
/// port's saver writes the reset at once. "odometer reset".
void reset_odometer(Controller& controller, const Origin& from);

/// Overrides a wind stow for `minutes` (0: wind.override_min); kNotFound
/// when the antenna is not stowed for the wind. "wind override [minutes]".
Error wind_override(Controller& controller, const Origin& from, int minutes);
/// Ends an override: the wind stow turns back to its heading; kNotFound
/// when no override runs. "wind stow".
Error end_wind_override(Controller& controller, const Origin& from);

}  // namespace rotord::command
