#pragma once
// The wind stow (issue 27, docs/care.md "Wind stow") over REST: its part of
// the status document, POST /api/wind/override and its /metrics rows.
#include "metrics/prometheus_writer.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

/// "wind": {...} in the status document (GET /api/status, the MQTT state):
/// the source, the last speed and direction, the state, the time left of
/// the calm or the override, the stow heading, the counts.
void write_wind_status(JsonWriter& w, const Controller& c);
/// POST /api/wind/override {"minutes": n} (optional; 0 or absent:
/// wind.override_min): lifts a stow's refusal for that long. {"end": true}
/// ends an override (stowed again if still windy). 409 when not stowed.
Api::Outcome post_wind_override(Api& api, const Api::Call& call);
/// The wind families of GET /metrics.
void write_wind_metrics(metrics::PrometheusWriter& w, const Controller& c);

}  // namespace rotord::web
