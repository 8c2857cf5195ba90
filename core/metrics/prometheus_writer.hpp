#pragma once
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string_view>

#include "metrics/histogram.hpp"
#include "util/byte_sink.hpp"

namespace rotord::metrics {

/// Streams the Prometheus text exposition format (version 0.0.4) into a
/// ByteSink through a small fixed buffer, as web::JsonWriter does for JSON:
/// GET /metrics is written while the control loop runs, on the Pico too, so
/// the page is never held in RAM and nothing is allocated. Hand-written
/// because no Prometheus client library runs without heap on a Cortex-M0+.
///
/// Usage: family() once per metric, then its samples, e.g.
///   w.family("rotord_axis_position_degrees", "gauge", "Position ...");
///   w.value({{"axis", "az"}}, 123.4);
class PrometheusWriter {
 public:
  struct Label {
    std::string_view name;
    std::string_view value;
  };

  /// `with_help` false leaves out the `# HELP` lines (optional in the
  /// format): a third of the page, for the Pico W's small TCP buffers.
  explicit PrometheusWriter(protocol::ByteSink& out, bool with_help = true)
      : out_(out), with_help_(with_help) {}
  ~PrometheusWriter() { flush(); }
  PrometheusWriter(const PrometheusWriter&) = delete;
  PrometheusWriter& operator=(const PrometheusWriter&) = delete;

  /// Starts a metric family: its `# HELP` and `# TYPE` lines. `type` is
  /// "gauge", "counter" or "histogram"; a counter's name ends in _total.
  PrometheusWriter& family(std::string_view name, std::string_view type, std::string_view help);
  /// A sample of the current family. NaN and infinities are written the
  /// way Prometheus reads them (NaN, +Inf, -Inf).
  PrometheusWriter& value(std::initializer_list<Label> labels, double v);
  PrometheusWriter& integer(std::initializer_list<Label> labels, std::uint64_t v);
  /// A whole histogram family from observations in microseconds, exposed in
  /// seconds (cumulative _bucket lines, +Inf, _sum, _count).
  PrometheusWriter& histogram_seconds(std::string_view name, std::string_view help,
                                      const Histogram& h);

  /// Microseconds as decimal seconds, exactly ("0.00005", "10", "-0.5").
  static std::size_t format_seconds(std::int64_t us, char* buf, std::size_t capacity);

 private:
  void begin_sample(std::string_view suffix, std::initializer_list<Label> labels,
                    const Label* extra = nullptr);
  void label_value(std::string_view v);
  void number(double v);
  void unsigned_integer(std::uint64_t v);
  void put(std::string_view s);
  void put(char c);
  void flush();

  protocol::ByteSink& out_;
  bool with_help_;
  std::string_view family_;
  char buf_[256];
  std::size_t len_ = 0;
};

}  // namespace rotord::metrics
