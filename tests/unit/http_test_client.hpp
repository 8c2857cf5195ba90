#pragma once
// Splits what an HttpSession wrote into responses, for the HTTP unit tests.
#include <cstdlib>
#include <string>
#include <vector>

#include "protocol/session.hpp"
#include "string_sink.hpp"

namespace rotord::testing {

struct HttpResponse {
  int status = 0;
  std::string head;  ///< status line and headers
  std::string body;
  /// The value of a header (case as the server writes it), or "".
  std::string header(const std::string& name) const {
    const auto pos = head.find("\r\n" + name + ": ");
    if (pos == std::string::npos) return "";
    const auto start = pos + name.size() + 4;
    return head.substr(start, head.find("\r\n", start) - start);
  }
};

/// Parses consecutive responses with Content-Length bodies; a response
/// without one takes the rest (an event stream).
/// The bytes of one POST request with a body, as a browser sends it.
inline std::string post_request(const std::string& path, const std::string& body,
                                const std::string& type = "application/json") {
  return "POST " + path + " HTTP/1.1\r\nHost: localhost\r\nContent-Type: " + type +
         "\r\nContent-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

inline std::vector<HttpResponse> parse_responses(std::string data) {
  std::vector<HttpResponse> out;
  while (!data.empty()) {
    HttpResponse r;
    const auto end = data.find("\r\n\r\n");
    if (end == std::string::npos || data.rfind("HTTP/1.1 ", 0) != 0) break;
    r.head = data.substr(0, end + 2);
    r.status = std::atoi(data.c_str() + 9);
    data.erase(0, end + 4);
    const std::string length = r.header("Content-Length");
    const std::size_t n = length.empty() ? data.size() : std::strtoul(length.c_str(), nullptr, 10);
    r.body = data.substr(0, n);
    data.erase(0, n);
    out.push_back(r);
  }
  return out;
}

}  // namespace rotord::testing
