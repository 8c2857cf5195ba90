// GET /metrics and GET /healthz: the Api's routes outside /api/, for
// Prometheus and for supervisors (docs/web_api.md#metrics).
#include "web/metrics_page.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
namespace {

/// Only GET and HEAD: these pages change nothing.
bool refuse_other_methods(const HttpRequest& request, protocol::ByteSink& out,
                          const ResponseOptions& options) {
  if (request.method == Method::kGet || request.method == Method::kHead) return false;
  ResponseOptions o = options;
  o.extra_headers = "Allow: GET, HEAD\r\n";
  send_error(out, 405, "method not allowed here", o);
  return true;
}

std::int64_t clock_now_us(const metrics::Registry* r) {
  return r != nullptr && r->clock != nullptr ? r->clock->now_us() : 0;
}

}  // namespace

void Api::handle_metrics(const HttpRequest& request, protocol::ByteSink& out,
                         const ResponseOptions& options) {
  if (refuse_other_methods(request, out, options)) return;
  // Written twice, first only counted for the Content-Length, so the page
  // never sits in RAM; one clock reading keeps both passes the same.
  const std::int64_t now_us = clock_now_us(ctx_.metrics);
  const bool help = ctx_.metrics == nullptr || ctx_.metrics->help_text;
  CountingSink counter;
  {
    metrics::PrometheusWriter w(counter, help);
    write_metrics(w, ctx_.controller, ctx_.metrics, ctx_.version, now_us);
  }
  ResponseOptions o = options;
  o.extra_headers = "Cache-Control: no-store\r\n";
  write_head(out, 200, "text/plain; version=0.0.4; charset=utf-8",
             static_cast<long>(counter.count()), o);
  if (options.head_only) return;
  metrics::PrometheusWriter w(out, help);
  write_metrics(w, ctx_.controller, ctx_.metrics, ctx_.version, now_us);
}

void Api::handle_health(const HttpRequest& request, protocol::ByteSink& out,
                        const ResponseOptions& options) {
  if (refuse_other_methods(request, out, options)) return;
  const Health h = check_health(ctx_.controller, ctx_.metrics, clock_now_us(ctx_.metrics));
  ResponseOptions o = options;
  o.extra_headers = "Cache-Control: no-store\r\n";
  send_json(out, h.ok ? 200 : 503, o, [&](JsonWriter& w) {
    w.begin_object().member("status", h.ok ? "ok" : "unhealthy");
    if (!h.ok) w.member("reason", h.reason);
    w.end_object();
  });
}

}  // namespace rotord::web
