#include "json/json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace rotord::web {

void CountingSink::write(std::string_view bytes) {
  count_ += bytes.size();
}

JsonWriter::JsonWriter(protocol::ByteSink& out) : out_(out) {}

JsonWriter& JsonWriter::member(std::string_view name, std::string_view s) {
  return key(name).string(s);
}
JsonWriter& JsonWriter::member(std::string_view name, const char* s) {
  return key(name).string(s);
}
JsonWriter& JsonWriter::member(std::string_view name, double v) {
  return key(name).number(v);
}
JsonWriter& JsonWriter::member(std::string_view name, float v) {
  return key(name).number(v);
}
JsonWriter& JsonWriter::member(std::string_view name, int v) {
  return key(name).integer(v);
}
JsonWriter& JsonWriter::member(std::string_view name, long long v) {
  return key(name).integer(v);
}
JsonWriter& JsonWriter::member(std::string_view name, std::uint32_t v) {
  return key(name).integer(v);
}
JsonWriter& JsonWriter::member(std::string_view name, bool v) {
  return key(name).boolean(v);
}

void JsonWriter::put(char c) {
  if (len_ == sizeof(buf_)) flush();
  buf_[len_++] = c;
}

void JsonWriter::put(std::string_view s) {
  for (char c : s) put(c);
}

void JsonWriter::flush() {
  if (len_ == 0) return;
  out_.write(std::string_view(buf_, len_));
  len_ = 0;
}

void JsonWriter::indent() {
  if (!pretty_) return;
  put('\n');
  for (int n = 0; n < depth_; ++n) put("  ");
}

void JsonWriter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (!first_[depth_]) put(',');
  if (depth_ > 0) indent();
  first_[depth_] = false;
}

JsonWriter& JsonWriter::begin_object() {
  before_value();
  put('{');
  if (depth_ < kMaxDepth) first_[++depth_] = true;
  return *this;
}

JsonWriter& JsonWriter::end_object() {
  const bool empty = first_[depth_];
  if (depth_ > 0) --depth_;
  if (!empty) indent();
  put('}');
  return *this;
}

JsonWriter& JsonWriter::begin_array() {
  before_value();
  put('[');
  if (depth_ < kMaxDepth) first_[++depth_] = true;
  return *this;
}

JsonWriter& JsonWriter::end_array() {
  const bool empty = first_[depth_];
  if (depth_ > 0) --depth_;
  if (!empty) indent();
  put(']');
  return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
  string(name);
  put(pretty_ ? ": " : ":");
  after_key_ = true;
  return *this;
}

JsonWriter& JsonWriter::string(std::string_view s) {
  before_value();
  put('"');
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      put('\\');
      put(c);
    } else if (c == '\n') {
      put("\\n");
    } else if (c == '\r') {
      put("\\r");
    } else if (c == '\t') {
      put("\\t");
    } else if (u < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof(esc), "\\u%04x", u);
      put(esc);
    } else {
      put(c);
    }
  }
  put('"');
  return *this;
}

JsonWriter& JsonWriter::number(double value) {
  if (!std::isfinite(value)) return null();
  before_value();
  char text[32];
  // %.7g keeps a float's precision; -0 prints as 0 so clients never see "-0".
  const int n = std::snprintf(text, sizeof(text), "%.7g", value == 0.0 ? 0.0 : value);
  if (n > 0) put(std::string_view(text, static_cast<std::size_t>(n)));
  return *this;
}

JsonWriter& JsonWriter::integer(long long value) {
  before_value();
  // By hand: newlib-nano's printf (the Pico's) has no %lld.
  char text[24];
  std::size_t n = sizeof(text);
  unsigned long long magnitude = value < 0 ? 0ull - static_cast<unsigned long long>(value)
                                           : static_cast<unsigned long long>(value);
  do {
    text[--n] = static_cast<char>('0' + magnitude % 10);
    magnitude /= 10;
  } while (magnitude != 0);
  if (value < 0) text[--n] = '-';
  put(std::string_view(text + n, sizeof(text) - n));
  return *this;
}

JsonWriter& JsonWriter::boolean(bool value) {
  before_value();
  put(value ? "true" : "false");
  return *this;
}

JsonWriter& JsonWriter::null() {
  before_value();
  put("null");
  return *this;
}

JsonWriter& JsonWriter::raw_value(std::string_view json) {
  before_value();
  put(json);
  return *this;
}

}  // namespace rotord::web
