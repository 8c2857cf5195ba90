#include "web/auth_body.hpp"

#include <cstdio>
#include <cstring>

#include "access/web_sessions.hpp"

namespace rotord::web {

bool read_body(std::string_view body, std::span<JsonMember> fields, protocol::ByteSink& out,
               const ResponseOptions& options) {
  char why[120];
  if (read_members(body, fields, why, sizeof why)) return true;
  send_error(out, 400, why, options);
  return false;
}

std::string_view session_cookie(char (&buf)[160], const char* id, long max_age_s) {
  const int n = std::snprintf(
      buf, sizeof buf, "Set-Cookie: %.*s=%s; Path=/; Max-Age=%ld; HttpOnly; SameSite=Strict\r\n",
      static_cast<int>(access::WebSessions::kCookieName.size()),
      access::WebSessions::kCookieName.data(), id != nullptr ? id : "",
      id != nullptr ? max_age_s : 0);
  if (n <= 0 || static_cast<std::size_t>(n) >= sizeof buf) return {};
  return {buf, static_cast<std::size_t>(n)};
}

long session_seconds(const settings::Settings& s) {
  return static_cast<long>(s.i(settings::Id::kWebSessionMinutes)) * 60;
}

}  // namespace rotord::web
