// The REST API's bearer tokens and the control lock (docs/web_api.md,
// "Access control", "Control lock"), and GET /api/auth.
#include <cstdio>
#include <cstring>

#include "web/auth_body.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

using settings::Id;

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
  char name[access::TokenRecord::kMaxNameBytes + 1] = {};  // a longer one is too long
  JsonMember fields[] = {{"name", JsonType::kString, name}, {"scope", JsonType::kString}};
  if (!read_body(request.body, fields, out, options)) return;
  if (!fields[0].present || !access::valid_token_name(name)) {
    send_error(out, 422, "name: 1 to 16 letters, digits, '-', '_' or '.'", options);
    return;
  }
  const std::string_view scope_text = fields[1].present ? fields[1].value.text : "read";
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
    } else if (std::string_view(record.name) == name) {
      send_error(out, 409, "a token of that name exists: revoke it first", options);
      return;
    }
  }
  if (free_row == nullptr) {
    send_error(out, 409, "every token slot is in use: revoke one first", options);
    return;
  }
  access::TokenRecord record;
  std::memcpy(record.name, name, sizeof record.name - 1);
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
  char name[access::TokenRecord::kMaxNameBytes + 1] = {};
  JsonMember fields[] = {{"name", JsonType::kString, name}};
  if (!read_body(request.body, fields, out, options)) return;
  settings::Settings& values = ctx_.controller.settings();
  for (Id row : kTokenRows) {
    access::TokenRecord record;
    if (!access::parse_token_record(values.text(row), record) ||
        std::string_view(record.name) != name)
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
  JsonMember fields[] = {{"minutes", JsonType::kNumber}};
  if (!read_body(request.body, fields, out, options)) return;
  const double minutes = fields[0].present ? fields[0].value.number : 10;
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
