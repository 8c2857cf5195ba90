#include "http_client.hpp"

#include <cstdlib>

#include "daemon_process.hpp"

namespace rotord::testing {

HttpResponse http(int port, const std::string& method, const std::string& path,
                  const std::string& body, const std::string& type) {
  return http_from("", port, method, path, body, type);
}

HttpResponse http_from(const std::string& source, int port, const std::string& method,
                       const std::string& path, const std::string& body, const std::string& type) {
  TcpClient c(port, source);
  HttpResponse r;
  if (!c.connected()) return r;
  std::string req = method + " " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n";
  if (!type.empty() && method == "POST") req += "Content-Type: " + type + "\r\n";
  if (method == "POST") req += "Content-Length: " + std::to_string(body.size()) + "\r\n";
  c.send(req + "\r\n" + body);
  c.wait_closed(10000);
  const std::string raw = c.recv_once(0);
  const auto end = raw.find("\r\n\r\n");
  if (raw.rfind("HTTP/1.1 ", 0) != 0 || end == std::string::npos) return r;
  r.status = std::atoi(raw.c_str() + 9);
  r.head = raw.substr(0, end);
  r.body = raw.substr(end + 4);
  return r;
}

double json_number(const std::string& json, const std::string& key, std::size_t from) {
  const auto pos = json.find("\"" + key + "\":", from);
  if (pos == std::string::npos) return -1e9;
  return std::strtod(json.c_str() + pos + key.size() + 3, nullptr);
}

}  // namespace rotord::testing
