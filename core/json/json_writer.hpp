#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "util/byte_sink.hpp"

// The JSON codec layer (core/json, docs/architecture.md): below web and storage,
// which both read and write JSON. Its names stayed in rotord::web, where the
// codec began, so the web API, the ports and the tests spell them as before.
namespace rotord::web {

/// A ByteSink that only counts, so a response body can be generated twice:
/// once to learn its Content-Length, once to send it. That keeps large bodies
/// (the settings schema) out of RAM on the Pico.
class CountingSink final : public protocol::ByteSink {
 public:
  // Out of line (json_writer.cpp), the key function: one vtable for the
  // core rather than one in every object that measures a body.
  void write(std::string_view bytes) override;
  std::size_t count() const { return count_; }

 private:
  std::size_t count_ = 0;
};

/// Streams JSON into a ByteSink through a small fixed buffer; commas and
/// nesting are tracked so callers only say what comes next. Hand-written
/// rather than nlohmann-json because it runs on the Cortex-M0+ without heap
/// (the responses are built while the control loop runs) and in a few hundred
/// bytes of flash.
class JsonWriter {
 public:
  static constexpr int kMaxDepth = 8;

  // The constructor and the shorthands below are out of line (json_writer.cpp):
  // some twenty files write JSON, and each kept a copy of them.
  explicit JsonWriter(protocol::ByteSink& out);
  ~JsonWriter() { flush(); }
  JsonWriter(const JsonWriter&) = delete;
  JsonWriter& operator=(const JsonWriter&) = delete;

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  /// The name of the next member of the current object.
  JsonWriter& key(std::string_view name);

  JsonWriter& string(std::string_view s);
  /// Non-finite numbers are written as null (JSON has no NaN).
  JsonWriter& number(double value);
  JsonWriter& integer(long long value);
  JsonWriter& boolean(bool value);
  JsonWriter& null();

  // Shorthands for one member.
  JsonWriter& member(std::string_view name, std::string_view s);
  JsonWriter& member(std::string_view name, const char* s);
  JsonWriter& member(std::string_view name, double v);
  JsonWriter& member(std::string_view name, float v);
  JsonWriter& member(std::string_view name, int v);
  JsonWriter& member(std::string_view name, long long v);
  JsonWriter& member(std::string_view name, std::uint32_t v);
  JsonWriter& member(std::string_view name, bool v);

  /// One member or element per line, indented: for files people edit by hand.
  void set_pretty(bool pretty) { pretty_ = pretty; }

  /// Copies already-formatted JSON text (e.g. a number from Settings::format).
  JsonWriter& raw_value(std::string_view json);
  void flush();

 private:
  void before_value();
  void put(std::string_view s);
  void put(char c);
  void indent();

  protocol::ByteSink& out_;
  char buf_[128];
  std::size_t len_ = 0;
  int depth_ = 0;
  bool first_[kMaxDepth + 1] = {true};
  bool after_key_ = false;
  bool pretty_ = false;
};

}  // namespace rotord::web
