#pragma once
// Looked after unattended (issue 27, docs/care.md): the wear odometer and
// the starts ceiling in the status document, GET/POST /api/odometer and
// their /metrics rows. Route handlers for web_api.cpp's table, kept apart
// from the Api class's own file.
#include "metrics/prometheus_writer.hpp"
#include "metrics/registry.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

/// GET /api/odometer: every count of each axis, the faults by kind, when it
/// was last reset, the save interval and the writes.
Api::Outcome get_odometer(Api& api, const Api::Call& call);
/// POST /api/odometer/reset: every count back to zero, dated (UTC when the
/// clock is known); written to storage at once.
Api::Outcome post_odometer_reset(Api& api, const Api::Call& call);

/// "odometer": {...} in the status document (GET /api/status, the MQTT
/// state): the counts of each axis (faults listed by kind only when some
/// were counted, the state stays short) and the starts ceiling.
void write_odometer_status(JsonWriter& w, const Controller& c);

/// The odometer's and the ceiling's families in GET /metrics.
void write_care_metrics(metrics::PrometheusWriter& w, const Controller& c,
                        const metrics::Registry* registry);

}  // namespace rotord::web
