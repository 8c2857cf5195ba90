#pragma once
#include <cstddef>
#include <string_view>

#include "json/json_writer.hpp"
#include "util/byte_sink.hpp"

namespace rotord::web {

const char* status_text(int status);

/// How one response goes out.
struct ResponseOptions {
  bool keep_alive = true;
  bool head_only = false;            ///< HEAD: headers only
  std::string_view extra_headers{};  ///< complete lines, each ending in CRLF
};

/// Writes the status line and headers. A length of -1 means no
/// Content-Length: the body runs until the connection closes (event streams).
void write_head(protocol::ByteSink& out, int status, std::string_view content_type, long length,
                const ResponseOptions& options);

/// A complete JSON response. `body(JsonWriter&)` runs twice: first into a
/// counter for the Content-Length, then into the connection, so even the
/// 20 KB schema never sits in RAM.
template <typename Body>
void send_json(protocol::ByteSink& out, int status, const ResponseOptions& options, Body&& body) {
  CountingSink counter;
  {
    JsonWriter w(counter);
    body(w);
  }
  write_head(out, status, "application/json", static_cast<long>(counter.count()), options);
  if (options.head_only) return;
  JsonWriter w(out);
  body(w);
}

/// {"error": message} with the given status.
void send_error(protocol::ByteSink& out, int status, std::string_view message,
                const ResponseOptions& options);

}  // namespace rotord::web
