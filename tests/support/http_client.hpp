#pragma once
#include <string>

namespace rotord::testing {

struct HttpResponse {
  int status = 0;  ///< 0: no (or no valid) response
  std::string head;
  std::string body;
};

/// One HTTP/1.1 request on its own loopback connection (Connection: close),
/// read to the end.
HttpResponse http(int port, const std::string& method, const std::string& path,
                  const std::string& body = "", const std::string& type = "application/json");
/// The same from another loopback address (e.g. "127.0.0.2"), another host
/// as the server's per-address limit sees it.
HttpResponse http_from(const std::string& source, int port, const std::string& method,
                       const std::string& path, const std::string& body = "",
                       const std::string& type = "application/json");

/// The number after "key": in a JSON text (searched from `from`), or -1e9.
double json_number(const std::string& json, const std::string& key, std::size_t from = 0);

}  // namespace rotord::testing
