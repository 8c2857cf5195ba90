#include "web/auth_body.hpp"

#include <cstdio>
#include <cstring>

#include "access/web_sessions.hpp"

namespace rotord::web {

bool read_body(std::string_view body, std::span<BodyField> fields, protocol::ByteSink& out,
               const ResponseOptions& options) {
  if (body.empty()) return true;
  JsonObjectReader reader(body);
  if (!reader.valid()) {
    char message[120];
    std::snprintf(message, sizeof message, "invalid JSON: %s", reader.error());
    send_error(out, 400, message, options);
    return false;
  }
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    BodyField* found = nullptr;
    for (BodyField& f : fields)
      if (key == f.name) found = &f;
    if (found == nullptr || value.type != found->type) {
      char message[120];
      if (found == nullptr) {
        std::snprintf(message, sizeof message, "unknown member '%.*s'",
                      static_cast<int>(key.size() > 40 ? 40 : key.size()), key.data());
      } else {
        std::snprintf(message, sizeof message, "%s must be a %s", found->name,
                      json_type_name(found->type));
      }
      send_error(out, 400, message, options);
      return false;
    }
    found->present = true;
    if (value.type == JsonType::kNumber) found->number = value.number;
    if (value.type == JsonType::kString) {
      found->too_long = value.truncated || value.text.size() >= sizeof found->text;
      const std::size_t n = found->too_long ? 0 : value.text.size();
      std::memcpy(found->text, value.text.data(), n);
      found->text[n] = '\0';
    }
  }
  return true;
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
