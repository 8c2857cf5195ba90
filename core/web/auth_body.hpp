#pragma once
// What the access-control endpoints (auth_api.cpp, token_api.cpp) share:
// reading their small bodies (the one member loop, json/json_members.hpp,
// with a 400 for what it refuses), the session cookie.
#include <cstddef>
#include <span>
#include <string_view>

#include "json/json_members.hpp"
#include "settings/settings.hpp"
#include "util/byte_sink.hpp"
#include "web/http_response.hpp"

namespace rotord::web {

/// A password's buffer: 8 to 63 characters fit, with room to tell a longer
/// one (JsonMember::too_long) from one that fits.
using PasswordText = char[72];

/// Reads `body` (empty = {}) into `fields` (json/json_members.hpp); on
/// failure the 400 has gone out and it returns false.
bool read_body(std::string_view body, std::span<JsonMember> fields, protocol::ByteSink& out,
               const ResponseOptions& options);

/// "Set-Cookie: rotord_session=...; ..." for a session, or the header that
/// deletes the cookie when `id` is null. HttpOnly: no script reads it;
/// SameSite=Strict: no other site's page makes the browser send it.
std::string_view session_cookie(char (&buf)[160], const char* id, long max_age_s);

/// How long a web session lasts (web.session_minutes).
long session_seconds(const settings::Settings& s);

}  // namespace rotord::web
