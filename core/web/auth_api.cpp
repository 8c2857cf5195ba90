// The access-control endpoints of the REST API (docs/web_api.md#access-control):
// login and logout, the web password, bearer tokens and the control lock.
// Gating every other route is in web_api.cpp (its route table).
#include <algorithm>
#include <cstdio>
#include <cstring>

#include "access/device_cookie.hpp"
#include "json/json_reader.hpp"
#include "settings/network_list.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
namespace {

using settings::Id;

/// A small body's string and number members, read by name. On failure the
/// 400 has gone out.
struct BodyField {
  const char* name;
  JsonType type;
  bool present = false;
  char text[72] = {};  ///< strings: the value (a password of up to 63 bytes fits)
  bool too_long = false;
  double number = 0.0;
};

template <std::size_t N>
bool read_body(std::string_view body, BodyField (&fields)[N], protocol::ByteSink& out,
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

/// "Set-Cookie: rotord_session=...; ..." for a session, or the header that
/// deletes the cookie when `id` is null. HttpOnly: no script reads it;
/// SameSite=Strict: no other site's page makes the browser send it.
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
  return static_cast<long>(s.i(Id::kWebSessionMinutes)) * 60;
}

}  // namespace

void Api::write_lock(JsonWriter& w, const Caller* caller) const {
  const access::ControlLock& lock = ctx_.controller.control_lock();
  w.begin_object().member("held", lock.held());
  if (caller != nullptr)
    w.member("mine", lock.held() && caller->can_hold_lock() && lock.held_by(caller->holder));
  w.key("by");
  if (!lock.held()) {
    w.null();
  } else if (lock.holder().kind == access::LockHolder::Kind::kToken) {
    char by[32];
    std::snprintf(by, sizeof by, "token %s", lock.holder().label);
    w.string(by);
  } else {
    w.string("web session");
  }
  const Millis left =
      lock.held() && lock.until() > transport_now_ ? lock.until() - transport_now_ : 0;
  w.member("remaining_s", static_cast<long long>((left + 999) / 1000)).end_object();
}

void Api::send_locked(protocol::ByteSink& out, const ResponseOptions& options) {
  send_error(out, 423, commands_.locked_refusal().message, options);
}

Api::Outcome Api::login(const HttpRequest& request, protocol::ByteSink& out,
                        const ResponseOptions& options, const access::Peer& peer) {
  BodyField fields[] = {{"password", JsonType::kString}};
  if (!read_body(request.body, fields, out, options)) return Outcome::kDone;
  if (!fields[0].present) {
    send_error(out, 400, "give password", options);
    return Outcome::kDone;
  }
  const settings::Settings& values = settings();
  access::PasswordHash stored;
  if (!WebAuth::enabled(values) ||
      !access::parse_password_hash(values.text(Id::kWebPassword), stored)) {
    send_error(out, 409, "access control is off: no web password is set", options);
    return Outcome::kDone;
  }
  if (ctx_.crypto == nullptr) {
    send_error(out, 503, "this build has no cryptography", options);
    return Outcome::kDone;
  }
  // Who guesses: a browser that logged in before (its device cookie), an
  // address on the allow-list, or a stranger; each class has a budget of its
  // own, so strangers guessing from many addresses never lock the owner out.
  const bool device = access::DeviceCookie::valid(*ctx_.crypto, stored, request.cookie);
  const std::string_view networks = values.text(Id::kAccessControlNetworks);
  const bool listed = !device && peer.kind == access::Peer::Kind::kIpv4 && !networks.empty() &&
                      !values.access_unreadable() && settings::in_network_list(networks, peer.ipv4);
  const WebAuth::Guesser who = device   ? WebAuth::Guesser::kDevice
                               : listed ? WebAuth::Guesser::kListed
                                        : WebAuth::Guesser::kStranger;
  // A recognised browser is exempt from its address's lock-out (OWASP).
  const Millis wait = device ? 0 : auth_.limiter().wait_ms(peer, transport_now_);
  const Millis budget_wait = auth_.budget(who).wait_ms(transport_now_);
  if (wait > 0 || budget_wait > 0) {
    count_auth_failure(false);
    char retry[40];
    char message[96];
    const long seconds = static_cast<long>((std::max(wait, budget_wait) + 999) / 1000);
    std::snprintf(retry, sizeof retry, "Retry-After: %ld\r\n", seconds);
    std::snprintf(message, sizeof message, "%s: try again in %ld s",
                  wait > 0 ? "too many failed logins" : "too many logins being tried", seconds);
    ResponseOptions o = options;
    o.extra_headers = retry;
    send_error(out, 429, message, o);
    return Outcome::kDone;
  }
  // One hash at a time: a second login waits its turn by retrying, except
  // the owner's, which a stranger's gives way to.
  if (who != WebAuth::Guesser::kStranger) auth_.preempt_for_trusted();
  if (auth_.start(WebAuth::JobKind::kLogin, fields[0].too_long ? "" : fields[0].text, stored, peer,
                  -1) == 0) {
    ResponseOptions o = options;
    o.extra_headers = "Retry-After: 1\r\n";
    send_error(out, 503, "busy checking another login: try again in a second", o);
    return Outcome::kDone;
  }
  auth_.budget(who).spend(transport_now_);
  auth_.job().trusted = who != WebAuth::Guesser::kStranger;
  if (fields[0].too_long) auth_.job().failed = auth_.job().computed = true;
  return Outcome::kPending;
}

void Api::logout(const Caller& caller, protocol::ByteSink& out, const ResponseOptions& options) {
  if (caller.kind == Caller::Kind::kSession) {
    access::ControlLock& lock = ctx_.controller.control_lock();
    if (lock.held_by(caller.holder)) lock.release();
    auth_.sessions().remove(caller.session);
  }
  char cookie[160];
  ResponseOptions o = options;
  o.extra_headers = session_cookie(cookie, nullptr, 0);
  send_json(out, 200, o, [](JsonWriter& w) { w.begin_object().member("ok", true).end_object(); });
}

Api::Outcome Api::set_password(const HttpRequest& request, protocol::ByteSink& out,
                               const ResponseOptions& options, const Caller& caller,
                               const access::Peer& peer) {
  BodyField fields[] = {{"password", JsonType::kString}};
  if (!read_body(request.body, fields, out, options)) return Outcome::kDone;
  if (!fields[0].present) {
    send_error(out, 400, "give password (\"\" turns access control off)", options);
    return Outcome::kDone;
  }
  settings::Settings& values = ctx_.controller.settings();
  char address[16];
  if (fields[0].text[0] == '\0' && !fields[0].too_long) {
    backup_ = values;
    values.set_text(Id::kWebPassword, "");
    if (!persist(out, options)) {
      values.copy_value(Id::kWebPassword, backup_);
      return Outcome::kDone;
    }
    auth_.log("rotord: web password removed by %s: access control is off",
              peer_text(peer, address));
    send_json(out, 200, options, [](JsonWriter& w) {
      w.begin_object().member("ok", true).member("enabled", false).end_object();
    });
    return Outcome::kDone;
  }
  const char* why = fields[0].too_long ? "the password may have at most 63 characters"
                                       : access::password_rule_violation(fields[0].text);
  if (why != nullptr) {
    send_error(out, 422, why, options);
    return Outcome::kDone;
  }
  access::PasswordHash target;
  target.iterations = ctx_.pbkdf2_iterations;
  if (ctx_.crypto == nullptr || !ctx_.crypto->random(target.salt)) {
    send_error(out, 503, "no cryptographic random numbers on this controller", options);
    return Outcome::kDone;
  }
  if (auth_.start(WebAuth::JobKind::kSetPassword, fields[0].text, target, peer,
                  caller.kind == Caller::Kind::kSession ? caller.session : -1) == 0) {
    ResponseOptions o = options;
    o.extra_headers = "Retry-After: 1\r\n";
    send_error(out, 503, "busy checking a login: try again in a second", o);
    return Outcome::kDone;
  }
  return Outcome::kPending;
}

void Api::work() {
  WebAuth::Job& job = auth_.job();
  if (job.kind == WebAuth::JobKind::kNone || job.completed) return;
  auth_.step(ctx_.pbkdf2_slice);
  if (job.computed) complete_job();
}

void Api::complete_job() {
  WebAuth::Job& job = auth_.job();
  job.completed = true;
  char address[16];
  const char* who = peer_text(job.peer, address);
  if (job.failed || ctx_.crypto == nullptr) {
    if (job.kind == WebAuth::JobKind::kLogin) {
      // A password too long to be the one counts as a wrong guess.
      const unsigned row = auth_.limiter().failed(job.peer, transport_now_);
      count_auth_failure(true);
      auth_.refused(job.peer, "rotord: failed web login from %s (%u in a row)", who, row);
      job.status = 401;
      job.message = "wrong password";
    } else {
      job.status = 500;
      job.message = "the password could not be hashed";
    }
    return;
  }
  const access::Sha256Digest& key = auth_.derived_key();
  if (job.kind == WebAuth::JobKind::kLogin) {
    const bool match = ctx_.crypto->equal(
        std::span<const std::uint8_t>(key.data(), access::PasswordHash::kKeyBytes), job.target.key);
    if (!match) {
      const unsigned row = auth_.limiter().failed(job.peer, transport_now_);
      count_auth_failure(true);
      auth_.refused(job.peer, "rotord: failed web login from %s (%u in a row)", who, row);
      job.status = 401;
      job.message = "wrong password";
      return;
    }
    auth_.limiter().succeeded(job.peer);
    job.new_session = auth_.sessions().create(*ctx_.crypto, transport_now_,
                                              session_seconds(settings()) * 1000, true);
    if (job.new_session < 0) {
      job.status = 503;
      job.message = "no cryptographic random numbers on this controller";
      return;
    }
    auth_.log("rotord: web login from %s", who);
    job.status = 200;
    return;
  }
  // kSetPassword: store the hash, log everyone else out.
  std::memcpy(job.target.key.data(), key.data(), job.target.key.size());
  char text[access::PasswordHash::kMaxTextBytes + 1];
  settings::Settings& values = ctx_.controller.settings();
  backup_ = values;
  if (access::format_password_hash(job.target, text, sizeof text) == 0 ||
      values.set_text(Id::kWebPassword, text).error != Error::kOk) {
    job.status = 500;
    job.message = "the password hash could not be stored";
    return;
  }
  if (!save()) {
    values.copy_value(Id::kWebPassword, backup_);
    job.status = 500;
    job.message = "the settings could not be saved; nothing was changed";
    return;
  }
  auth_.sessions().remove_all();
  ctx_.controller.control_lock().release();
  job.new_session =
      auth_.sessions().create(*ctx_.crypto, transport_now_, session_seconds(values) * 1000, true);
  auth_.log("rotord: web password set by %s: access control is on", who);
  job.status = 200;
}

bool Api::finish_pending(std::uint32_t ticket, protocol::ByteSink& out,
                         const ResponseOptions& options) {
  WebAuth::Job& job = auth_.job();
  if (job.ticket != ticket || job.claimed) {
    // Dropped for the owner's login (WebAuth::preempt_for_trusted).
    ResponseOptions o = options;
    o.extra_headers = "Retry-After: 1\r\n";
    send_error(out, 503, "busy checking another login: try again in a second", o);
    return true;
  }
  if (!job.completed) return false;
  job.claimed = true;
  if (job.status != 200) {
    send_error(out, job.status, job.message, options);
    return true;
  }
  char cookie[160];
  char id[access::WebSessions::kIdTextBytes + 1];
  char headers[400];
  ResponseOptions o = options;
  if (job.new_session >= 0) {
    auth_.sessions().id_text(job.new_session, id);
    const std::string_view session = session_cookie(cookie, id, session_seconds(settings()));
    // The browser that logged in is recognised from now on (its device
    // cookie, for as long as this password stands).
    access::PasswordHash stored;
    char device[access::DeviceCookie::kTextBytes + 1];
    int n = -1;
    if (ctx_.crypto != nullptr &&
        access::parse_password_hash(settings().text(Id::kWebPassword), stored) &&
        access::DeviceCookie::make(*ctx_.crypto, stored, device)) {
      n = std::snprintf(headers, sizeof headers,
                        "%.*sSet-Cookie: %.*s=%s; Path=/; Max-Age=%ld; HttpOnly; "
                        "SameSite=Strict\r\n",
                        static_cast<int>(session.size()), session.data(),
                        static_cast<int>(access::DeviceCookie::kCookieName.size()),
                        access::DeviceCookie::kCookieName.data(), device,
                        access::DeviceCookie::kMaxAgeSeconds);
    }
    o.extra_headers = n > 0 && static_cast<std::size_t>(n) < sizeof headers
                          ? std::string_view(headers, static_cast<std::size_t>(n))
                          : session;
  }
  const bool password = job.kind == WebAuth::JobKind::kSetPassword;
  send_json(out, 200, o, [password](JsonWriter& w) {
    w.begin_object().member("ok", true);
    if (password) w.member("enabled", true);
    w.end_object();
  });
  std::memset(id, 0, sizeof id);
  return true;
}

void Api::abandon_pending(std::uint32_t ticket) {
  WebAuth::Job& job = auth_.job();
  // The work goes on in poll() (a failed guess still counts, a new password
  // is still stored); only the response has nobody to go to.
  if (job.ticket == ticket) job.claimed = true;
}

bool Api::page_allowed(const HttpRequest& request) {
  if (!WebAuth::enabled(settings())) return true;
  // The login page and what it loads.
  for (const char* open : {"/login.html", "/login.js", "/style.css"})
    if (request.path == open) return true;
  return auth_.identify(request, settings(), transport_now_).may_read();
}

bool Api::still_allowed(const Caller& caller) const {
  if (!WebAuth::enabled(ctx_.controller.settings())) return true;
  if (caller.kind == Caller::Kind::kSession) {
    const access::WebSessions::Entry& e = auth_.sessions().at(caller.session);
    return e.used && e.authenticated && e.expires > transport_now_ &&
           std::memcmp(e.id.data(), caller.holder.key.data(), caller.holder.key.size()) == 0;
  }
  if (caller.kind == Caller::Kind::kToken) {
    access::TokenRecord record;
    return access::parse_token_record(ctx_.controller.settings().text(kTokenRows[caller.token]),
                                      record) &&
           std::memcmp(record.hash.data(), caller.holder.key.data(), caller.holder.key.size()) == 0;
  }
  return false;
}

void Api::get_auth(const Caller& caller, protocol::ByteSink& out, const ResponseOptions& options) {
  const bool enabled = WebAuth::enabled(settings());
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object().member("enabled", enabled).member("logged_in", caller.logged_in);
    w.member("via", caller.kind == Caller::Kind::kToken     ? "token"
                    : caller.kind == Caller::Kind::kSession ? "session"
                                                            : "none");
    w.key("token");
    if (caller.kind == Caller::Kind::kToken) {
      w.string(caller.token_name);
    } else {
      w.null();
    }
    const bool controls = !enabled || caller.may_control();
    w.member("may_control", controls).member("may_administer", !enabled || caller.may_administer());
    w.key("lock");
    write_lock(w, &caller);
    w.end_object();
  });
}

void Api::get_tokens(protocol::ByteSink& out, const ResponseOptions& options) {
  const settings::Settings& values = settings();
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object().key("tokens").begin_array();
    for (Id row : kTokenRows) {
      access::TokenRecord record;
      if (!access::parse_token_record(values.text(row), record)) continue;
      w.begin_object()
          .member("name", record.name)
          .member("scope", access::scope_name(record.scope))
          .end_object();
    }
    w.end_array().member("max", static_cast<int>(std::size(kTokenRows))).end_object();
  });
}

void Api::create_token(const HttpRequest& request, protocol::ByteSink& out,
                       const ResponseOptions& options) {
  BodyField fields[] = {{"name", JsonType::kString}, {"scope", JsonType::kString}};
  if (!read_body(request.body, fields, out, options)) return;
  if (!fields[0].present || !access::valid_token_name(fields[0].text)) {
    send_error(out, 422, "name: 1 to 16 letters, digits, '-', '_' or '.'", options);
    return;
  }
  const std::string_view scope_text = fields[1].present ? fields[1].text : "read";
  if (scope_text != "read" && scope_text != "control") {
    send_error(out, 422, "scope must be read or control", options);
    return;
  }
  settings::Settings& values = ctx_.controller.settings();
  const Id* free_row = nullptr;
  for (const Id& row : kTokenRows) {
    access::TokenRecord record;
    if (!access::parse_token_record(values.text(row), record)) {
      if (free_row == nullptr) free_row = &row;
    } else if (std::string_view(record.name) == fields[0].text) {
      send_error(out, 409, "a token of that name exists: revoke it first", options);
      return;
    }
  }
  if (free_row == nullptr) {
    send_error(out, 409, "every token slot is in use: revoke one first", options);
    return;
  }
  access::TokenRecord record;
  std::memcpy(record.name, fields[0].text, sizeof record.name - 1);
  record.scope = scope_text == "control" ? access::Scope::kControl : access::Scope::kRead;
  char token[access::kTokenTextBytes + 1];
  char text[80];
  if (ctx_.crypto == nullptr || !access::make_token(*ctx_.crypto, token, record.hash) ||
      access::format_token_record(record, text, sizeof text) == 0) {
    send_error(out, 503, "no cryptographic random numbers on this controller", options);
    return;
  }
  backup_ = values;
  values.set_text(*free_row, text);
  if (!persist(out, options)) {
    values.copy_value(*free_row, backup_);
    return;
  }
  auth_.log("rotord: REST token '%s' (%s) created", record.name, access::scope_name(record.scope));
  // The only time the token is shown: only its hash is kept.
  send_json(out, 201, options, [&](JsonWriter& w) {
    w.begin_object()
        .member("ok", true)
        .member("name", record.name)
        .member("scope", access::scope_name(record.scope))
        .member("token", token)
        .end_object();
  });
  std::memset(token, 0, sizeof token);
}

void Api::revoke_token(const HttpRequest& request, protocol::ByteSink& out,
                       const ResponseOptions& options) {
  BodyField fields[] = {{"name", JsonType::kString}};
  if (!read_body(request.body, fields, out, options)) return;
  settings::Settings& values = ctx_.controller.settings();
  for (Id row : kTokenRows) {
    access::TokenRecord record;
    if (!access::parse_token_record(values.text(row), record) ||
        std::string_view(record.name) != fields[0].text)
      continue;
    backup_ = values;
    values.set_text(row, "");
    if (!persist(out, options)) {
      values.copy_value(row, backup_);
      return;
    }
    access::ControlLock& lock = ctx_.controller.control_lock();
    if (lock.held() && lock.holder().kind == access::LockHolder::Kind::kToken &&
        std::memcmp(lock.holder().key.data(), record.hash.data(), lock.holder().key.size()) == 0)
      lock.release();
    auth_.log("rotord: REST token '%s' revoked", record.name);
    send_json(out, 200, options,
              [](JsonWriter& w) { w.begin_object().member("ok", true).end_object(); });
    return;
  }
  send_error(out, 404, "no token of that name", options);
}

void Api::lock(const HttpRequest& request, protocol::ByteSink& out, const ResponseOptions& options,
               Caller caller) {
  BodyField fields[] = {{"minutes", JsonType::kNumber}};
  if (!read_body(request.body, fields, out, options)) return;
  const double minutes = fields[0].present ? fields[0].number : 10;
  if (minutes != static_cast<int>(minutes) || minutes < 1 ||
      minutes * 60000 > static_cast<double>(access::ControlLock::kMaxHoldMs)) {
    send_error(out, 422, "minutes must be a whole number 1..240", options);
    return;
  }
  access::ControlLock& lock = ctx_.controller.control_lock();
  if (lock.held() && (!caller.can_hold_lock() || !lock.held_by(caller.holder))) {
    send_locked(out, options);
    return;
  }
  char cookie[160];
  char id[access::WebSessions::kIdTextBytes + 1];
  ResponseOptions o = options;
  if (!caller.can_hold_lock()) {
    // Access control is off (else the route table refused): the lock needs
    // someone to belong to, so the browser or script gets a session cookie.
    const int session = ctx_.crypto == nullptr
                            ? -1
                            : auth_.sessions().create(*ctx_.crypto, transport_now_,
                                                      session_seconds(settings()) * 1000, false);
    if (session < 0) {
      send_error(out, 503, "no cryptographic random numbers on this controller", options);
      return;
    }
    caller.kind = Caller::Kind::kSession;
    caller.session = session;
    caller.holder.kind = access::LockHolder::Kind::kSession;
    std::memcpy(caller.holder.key.data(), auth_.sessions().at(session).id.data(),
                caller.holder.key.size());
    auth_.sessions().id_text(session, id);
    o.extra_headers = session_cookie(cookie, id, session_seconds(settings()));
  }
  const bool renewed = lock.held();
  lock.take(caller.holder, transport_now_ + static_cast<Millis>(minutes) * 60000);
  if (!renewed)
    auth_.log("rotord: control lock taken by %s for %d min",
              caller.kind == Caller::Kind::kToken ? caller.token_name : "a web session",
              static_cast<int>(minutes));
  send_json(out, 200, o, [&](JsonWriter& w) {
    w.begin_object().member("ok", true).key("lock");
    write_lock(w, &caller);
    w.end_object();
  });
}

void Api::unlock(const Caller& caller, protocol::ByteSink& out, const ResponseOptions& options) {
  access::ControlLock& lock = ctx_.controller.control_lock();
  if (lock.held()) {
    if (!caller.can_hold_lock() || !lock.held_by(caller.holder)) {
      send_locked(out, options);
      return;
    }
    lock.release();
    auth_.log("rotord: control lock released");
  }
  send_json(out, 200, options,
            [](JsonWriter& w) { w.begin_object().member("ok", true).end_object(); });
}

}  // namespace rotord::web
