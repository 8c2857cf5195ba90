// The access-control endpoints of the REST API (docs/web_api.md#access-control):
// login and logout, the web password, the slow hash they wait for. Tokens
// and the control lock are in token_api.cpp; gating every other route is in
// web_api.cpp (its route table).
#include <algorithm>
#include <cstdio>
#include <cstring>

#include "access/device_cookie.hpp"
#include "settings/network_list.hpp"
#include "web/auth_body.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

using settings::Id;

Api::Outcome Api::login(const HttpRequest& request, protocol::ByteSink& out,
                        const ResponseOptions& options, const access::Peer& peer) {
  PasswordText password = {};
  JsonMember fields[] = {{"password", JsonType::kString, password}};
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
  const bool listed = !device && !networks.empty() && !values.access_unreadable() &&
                      settings::in_network_list(networks, peer);
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
  if (auth_.start(WebAuth::JobKind::kLogin, password, stored, peer, -1) == 0) {
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
  PasswordText password = {};
  JsonMember fields[] = {{"password", JsonType::kString, password}};
  if (!read_body(request.body, fields, out, options)) return Outcome::kDone;
  if (!fields[0].present) {
    send_error(out, 400, "give password (\"\" turns access control off)", options);
    return Outcome::kDone;
  }
  settings::Settings& values = ctx_.controller.settings();
  char address[access::kAddressTextBytes];
  if (password[0] == '\0' && !fields[0].too_long) {
    backup_ = values;
    values.set_text(Id::kWebPassword, "");
    if (!persist(out, options)) {
      values.copy_value(Id::kWebPassword, backup_);
      return Outcome::kDone;
    }
    auth_.log("rotord: web password removed by %s: access control is off",
              access::peer_text(peer, address));
    send_json(out, 200, options, [](JsonWriter& w) {
      w.begin_object().member("ok", true).member("enabled", false).end_object();
    });
    return Outcome::kDone;
  }
  const char* why = fields[0].too_long ? "the password may have at most 63 characters"
                                       : access::password_rule_violation(password);
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
  if (auth_.start(WebAuth::JobKind::kSetPassword, password, target, peer,
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
  char address[access::kAddressTextBytes];
  const char* who = access::peer_text(job.peer, address);
  if (job.failed || ctx_.crypto == nullptr) {
    if (job.kind == WebAuth::JobKind::kLogin) {
      // A password too long to be the one counts as a wrong guess.
      fail_login(job, who);
    } else {
      job.status = 500;
      job.message = "the password could not be hashed";
    }
    return;
  }
  if (job.kind == WebAuth::JobKind::kLogin) {
    complete_login(job, who);
  } else {
    complete_password(job, who);
  }
}

void Api::fail_login(WebAuth::Job& job, const char* who) {
  const unsigned row = auth_.limiter().failed(job.peer, transport_now_);
  count_auth_failure(true);
  auth_.refused(job.peer, "rotord: failed web login from %s (%u in a row)", who, row);
  job.status = 401;
  job.message = "wrong password";
}

void Api::complete_login(WebAuth::Job& job, const char* who) {
  const access::Sha256Digest& key = auth_.derived_key();
  const bool match = ctx_.crypto->equal(
      std::span<const std::uint8_t>(key.data(), access::PasswordHash::kKeyBytes), job.target.key);
  if (!match) return fail_login(job, who);
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
}

void Api::complete_password(WebAuth::Job& job, const char* who) {
  // Store the hash, log everyone else out.
  const access::Sha256Digest& key = auth_.derived_key();
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

}  // namespace rotord::web
