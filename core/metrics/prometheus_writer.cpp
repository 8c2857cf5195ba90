#include "metrics/prometheus_writer.hpp"

#include <cmath>
#include <cstdio>

namespace rotord::metrics {

PrometheusWriter& PrometheusWriter::family(std::string_view name, std::string_view type,
                                           std::string_view help) {
  family_ = name;
  if (with_help_) {
    put("# HELP ");
    put(name);
    put(' ');
    for (char c : help) {
      // HELP text escapes only the backslash and the line feed.
      if (c == '\\') {
        put("\\\\");
      } else if (c == '\n') {
        put("\\n");
      } else {
        put(c);
      }
    }
    put('\n');
  }
  put("# TYPE ");
  put(name);
  put(' ');
  put(type);
  put('\n');
  return *this;
}

PrometheusWriter& PrometheusWriter::value(std::initializer_list<Label> labels, double v) {
  begin_sample({}, labels);
  number(v);
  put('\n');
  return *this;
}

PrometheusWriter& PrometheusWriter::integer(std::initializer_list<Label> labels, std::uint64_t v) {
  begin_sample({}, labels);
  unsigned_integer(v);
  put('\n');
  return *this;
}

PrometheusWriter& PrometheusWriter::histogram_seconds(std::string_view name, std::string_view help,
                                                      const Histogram& h) {
  family(name, "histogram", help);
  std::uint64_t cumulative = 0;
  char le[24];
  for (std::size_t n = 0; n < h.bounds_us().size(); ++n) {
    cumulative += h.bucket(n);
    const std::size_t len = format_seconds(h.bounds_us()[n], le, sizeof le);
    const Label bound{"le", std::string_view(le, len)};
    begin_sample("_bucket", {}, &bound);
    unsigned_integer(cumulative);
    put('\n');
  }
  const Label inf{"le", "+Inf"};
  begin_sample("_bucket", {}, &inf);
  unsigned_integer(h.count());
  put('\n');
  begin_sample("_sum", {});
  const std::size_t len = format_seconds(h.sum_us(), le, sizeof le);
  put(std::string_view(le, len));
  put('\n');
  begin_sample("_count", {});
  unsigned_integer(h.count());
  put('\n');
  return *this;
}

std::size_t PrometheusWriter::format_seconds(std::int64_t us, char* buf, std::size_t capacity) {
  // By hand, in integers: exact, and newlib-nano's printf (the Pico's) has
  // no %lld.
  char text[32];
  std::size_t n = sizeof text;
  const bool negative = us < 0;
  std::uint64_t magnitude =
      negative ? 0ull - static_cast<std::uint64_t>(us) : static_cast<std::uint64_t>(us);
  std::uint64_t fraction = magnitude % 1000000;
  std::uint64_t whole = magnitude / 1000000;
  if (fraction != 0) {
    int digits = 6;
    while (fraction % 10 == 0) {  // no trailing zeros
      fraction /= 10;
      --digits;
    }
    for (; digits > 0; --digits) {
      text[--n] = static_cast<char>('0' + fraction % 10);
      fraction /= 10;
    }
    text[--n] = '.';
  }
  do {
    text[--n] = static_cast<char>('0' + whole % 10);
    whole /= 10;
  } while (whole != 0);
  if (negative) text[--n] = '-';
  const std::size_t len = sizeof text - n;
  if (len > capacity) return 0;
  for (std::size_t i = 0; i < len; ++i) buf[i] = text[n + i];
  return len;
}

void PrometheusWriter::begin_sample(std::string_view suffix, std::initializer_list<Label> labels,
                                    const Label* extra) {
  put(family_);
  put(suffix);
  if (labels.size() == 0 && extra == nullptr) {
    put(' ');
    return;
  }
  put('{');
  bool first = true;
  auto one = [&](const Label& l) {
    if (!first) put(',');
    first = false;
    put(l.name);
    put("=\"");
    label_value(l.value);
    put('"');
  };
  for (const Label& l : labels) one(l);
  if (extra != nullptr) one(*extra);
  put("} ");
}

void PrometheusWriter::label_value(std::string_view v) {
  for (char c : v) {
    if (c == '\\' || c == '"') {
      put('\\');
      put(c);
    } else if (c == '\n') {
      put("\\n");
    } else {
      put(c);
    }
  }
}

void PrometheusWriter::number(double v) {
  if (std::isnan(v)) return put("NaN");
  if (std::isinf(v)) return put(v > 0 ? "+Inf" : "-Inf");
  char text[32];
  // %.9g: a float's digits and then some; -0 prints as 0.
  const int n = std::snprintf(text, sizeof text, "%.9g", v == 0.0 ? 0.0 : v);
  if (n > 0) put(std::string_view(text, static_cast<std::size_t>(n)));
}

void PrometheusWriter::unsigned_integer(std::uint64_t v) {
  char text[24];
  std::size_t n = sizeof text;
  do {
    text[--n] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  put(std::string_view(text + n, sizeof text - n));
}

void PrometheusWriter::put(std::string_view s) {
  while (!s.empty()) {
    if (len_ == sizeof buf_) flush();
    std::size_t n = sizeof buf_ - len_;
    if (n > s.size()) n = s.size();
    for (std::size_t i = 0; i < n; ++i) buf_[len_ + i] = s[i];
    len_ += n;
    s.remove_prefix(n);
  }
}

void PrometheusWriter::put(char c) {
  if (len_ == sizeof buf_) flush();
  buf_[len_++] = c;
}

void PrometheusWriter::flush() {
  if (len_ == 0) return;
  out_.write(std::string_view(buf_, len_));
  len_ = 0;
}

}  // namespace rotord::metrics
