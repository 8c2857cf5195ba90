#include "web/http_response.hpp"

#include <cstdio>

namespace rotord::web {
namespace {

/// On every response: no other site may frame the pages (clickjacking), the
/// pages load nothing from elsewhere, and types are not sniffed.
constexpr std::string_view kSecurityHeaders =
    "X-Frame-Options: DENY\r\n"
    "Content-Security-Policy: default-src 'self'; img-src 'self' data:; "
    "frame-ancestors 'none'; base-uri 'none'; form-action 'self'\r\n"
    "X-Content-Type-Options: nosniff\r\n"
    "Referrer-Policy: no-referrer\r\n";

}  // namespace

const char* status_text(int status) {
  switch (status) {
    case 200:
      return "OK";
    case 202:
      return "Accepted";
    case 304:
      return "Not Modified";
    case 400:
      return "Bad Request";
    case 404:
      return "Not Found";
    case 401:
      return "Unauthorized";
    case 403:
      return "Forbidden";
    case 405:
      return "Method Not Allowed";
    case 408:
      return "Request Timeout";
    case 409:
      return "Conflict";
    case 413:
      return "Content Too Large";
    case 414:
      return "URI Too Long";
    case 415:
      return "Unsupported Media Type";
    case 421:
      return "Misdirected Request";
    case 422:
      return "Unprocessable Content";
    case 431:
      return "Request Header Fields Too Large";
    case 500:
      return "Internal Server Error";
    case 501:
      return "Not Implemented";
    case 503:
      return "Service Unavailable";
    case 505:
      return "HTTP Version Not Supported";
    default:
      return "Unknown";
  }
}

void write_head(protocol::ByteSink& out, int status, std::string_view content_type, long length,
                const ResponseOptions& options) {
  // Room for the security headers and an asset's: one write, one segment.
  // 448 bytes of the Pico W's 4 KB stack, on a path measured at about 2 KB.
  char head[448];
  int n = std::snprintf(head, sizeof(head), "HTTP/1.1 %d %s\r\nContent-Type: %.*s\r\n", status,
                        status_text(status), static_cast<int>(content_type.size()),
                        content_type.data());
  if (n < 0 || static_cast<std::size_t>(n) >= sizeof(head)) return;
  std::size_t len = static_cast<std::size_t>(n);
  if (length >= 0) {
    n = std::snprintf(head + len, sizeof(head) - len, "Content-Length: %ld\r\n", length);
    if (n > 0) len += static_cast<std::size_t>(n);
  }
  n = std::snprintf(head + len, sizeof(head) - len, "Connection: %s\r\n",
                    options.keep_alive ? "keep-alive" : "close");
  if (n > 0) len += static_cast<std::size_t>(n);
  // Headers, extra headers and the blank line go out as one write: one segment
  // for the common small response.
  if (len + kSecurityHeaders.size() + options.extra_headers.size() + 2 <= sizeof(head)) {
    for (char c : kSecurityHeaders) head[len++] = c;
    for (char c : options.extra_headers) head[len++] = c;
    head[len++] = '\r';
    head[len++] = '\n';
    out.write(std::string_view(head, len));
    return;
  }
  out.write(std::string_view(head, len));
  out.write(kSecurityHeaders);
  out.write(options.extra_headers);
  out.write("\r\n");
}

void send_error(protocol::ByteSink& out, int status, std::string_view message,
                const ResponseOptions& options) {
  send_json(out, status, options,
            [&](JsonWriter& w) { w.begin_object().member("error", message).end_object(); });
}

}  // namespace rotord::web
