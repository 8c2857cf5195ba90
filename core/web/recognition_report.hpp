#pragma once

#include "json/json_writer.hpp"
#include "metrics/prometheus_writer.hpp"
#include "rotator/recognition.hpp"

namespace rotord::web {

/// GET /api/status "recognised": the object rotord follows in a client's
/// go-to stream (docs/tracking.md, "Trackers through the protocols"), or
/// the last one and when and why it ended; null when there never was one.
void write_recognition(JsonWriter& w, const Recognition& r);
/// GET /metrics: rotord_goto_recognised_total and rotord_goto_recognised.
void write_recognition_metrics(metrics::PrometheusWriter& w, const Recognition& r);

}  // namespace rotord::web
