#pragma once
// Where the beam points (issue 26): turning to a place, presets and the
// map's sky (docs/web_api.md, "Places, presets and the map"). Route handlers
// for web_api.cpp's table, kept apart from the Api class's own file; turning
// to a place or a preset is the command layer's (command/commands.hpp).
#include "web/web_api.hpp"

namespace rotord::web {

/// GET /api/place?locator=|lat=&lon=[&path=long]: the bearing and distance.
Api::Outcome get_place(Api& api, const Api::Call& call);
/// GET /api/sky: the station, the beamwidth, the Sun and the Moon.
Api::Outcome get_sky(Api& api, const Api::Call& call);

/// GET /api/presets: every preset.
Api::Outcome get_presets(Api& api, const Api::Call& call);
/// POST /api/presets {"name","az","long_path"}: adds or replaces one, saved.
Api::Outcome post_presets(Api& api, const Api::Call& call);
/// POST /api/presets/delete {"name"}: removes one, saved.
Api::Outcome delete_preset(Api& api, const Api::Call& call);

/// The beam's direction beside the mechanism's in a status document:
/// "beam": {"az_deg", "el_deg"} (null while the position is unknown).
void write_beam(JsonWriter& w, const RotatorStatus& s);

}  // namespace rotord::web
