#include "metrics/registry.hpp"

#include "protocol/gs232_session.hpp"

namespace rotord::metrics {

const char* protocol_label(Protocol protocol) {
  switch (protocol) {
    case Protocol::kHttp:
      return "http";
    case Protocol::kWrc:
      return "wrc";
    case Protocol::kRotctld:
      return "rotctld";
    case Protocol::kGs232:
      return "gs232";
    case Protocol::kEasycomm:
      return "easycomm";
    case Protocol::kSeed:
      return "seed";
    case Protocol::kConsole:
      return "console";
    case Protocol::kCount:
      break;
  }
  return "?";
}

namespace {

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.starts_with(prefix);
}

/// "HTTP/1.1 404 ..." and up: a status line of 400 or more.
bool is_http_error(std::string_view reply) {
  constexpr std::string_view kVersion = "HTTP/1.1 ";
  if (!starts_with(reply, kVersion) || reply.size() < kVersion.size() + 3) return false;
  const char first = reply[kVersion.size()];
  return first >= '4' && first <= '5';
}

}  // namespace

bool is_error_reply(Protocol protocol, std::string_view reply) {
  switch (protocol) {
    case Protocol::kHttp:
      return is_http_error(reply);
    case Protocol::kWrc:
      // MONITOR's pushed STATE lines and every OK reply start otherwise.
      return starts_with(reply, "ERROR");
    case Protocol::kRotctld:
      // Plain and extended replies alike end an error with a negative RPRT.
      return reply.find("RPRT -") != std::string_view::npos;
    case Protocol::kGs232:
      return reply == protocol::Gs232Session::kError;
    case Protocol::kEasycomm:
      return starts_with(reply, "AL");  // the alarm line, Easycomm's only error
    case Protocol::kSeed:
      return starts_with(reply, "$ERR");
    case Protocol::kConsole:
      return starts_with(reply, "error:");
    case Protocol::kCount:
      break;
  }
  return false;
}

}  // namespace rotord::metrics
