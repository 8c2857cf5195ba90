#pragma once
#include <cstddef>
#include <cstdint>

#include "metrics/prometheus_writer.hpp"
#include "metrics/registry.hpp"
#include "rotator/controller.hpp"

namespace rotord::web {

/// GET /metrics: the controller's state and counters and the port's
/// registry (connections, errors, ticks, saves) in the Prometheus text
/// format; every metric is listed in docs/web_api.md#metrics. `registry` may
/// be null (only the controller's metrics); `now_us` is its clock's reading.
void write_metrics(metrics::PrometheusWriter& w, const Controller& controller,
                   const metrics::Registry* registry, const char* version, std::int64_t now_us);

/// GET /healthz: healthy while the control loop ticked within
/// kMaxTickAgeUs and no axis has a position sensor fault.
struct Health {
  /// Ten missed periods: a loop this late is stuck or starved, not jittery.
  static constexpr std::int64_t kMaxTickAgeUs = 100'000;
  bool ok = true;
  char reason[96] = "";
};
Health check_health(const Controller& controller, const metrics::Registry* registry,
                    std::int64_t now_us);

}  // namespace rotord::web
