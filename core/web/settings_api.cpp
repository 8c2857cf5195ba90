// The settings over REST: GET/POST /api/settings, POST /api/settings/reset,
// and saving them (docs/web_api.md, "Settings"). Who may write which key,
// the checks and the log line are the command layer's
// (command/settings_commands.hpp); here are the bytes.
#include <cstdio>

#include "web/web_api.hpp"

namespace rotord::web {

using settings::Id;

void Api::get_settings(protocol::ByteSink& out, const ResponseOptions& options) {
  const settings::Settings& values = ctx_.controller.settings();
  send_json(out, 200, options, [&](JsonWriter& w) { write_settings(values, w); });
}

command::Store Api::store() {
  return {backup_, [](void* api) { return static_cast<Api*>(api)->save(); }, this};
}

Api::Outcome Api::post_settings(const Call& call) {
  // A control token changes the rotator's settings, never the access rules
  // or a secret: it cannot widen its own rights.
  const bool login = !WebAuth::enabled(settings()) || call.caller.may_administer();
  const command::Store saved = store();
  return send_set(call,
                  command::set_settings(ctx_.controller, {"rest", call.peer},
                                        login ? command::Writer::kLogin : command::Writer::kToken,
                                        call.request.body, {scratch_, errors_}, &saved),
                  422);
}

Api::Outcome Api::reset_settings(const Call& call) {
  if (ctx_.defaults == nullptr) scratch_.reset_to_defaults();
  const settings::Settings& defaults = ctx_.defaults != nullptr ? *ctx_.defaults : scratch_;
  return send_set(
      call, command::reset_settings(ctx_.controller, {"rest", call.peer}, defaults, store()), 422);
}

Api::Outcome Api::send_set(const Call& call, const command::SetResult& r, int refused_status) {
  char message[200];
  switch (r.status) {
    case command::SetResult::kRefused:
      count_auth_failure(false);
      std::snprintf(message, sizeof message, "%s needs the web login, not a token",
                    settings::def(r.key).key);
      send_error(call.out, 403, message, call.options);
      return Outcome::kDone;
    case command::SetResult::kBadJson:
      std::snprintf(message, sizeof message, "invalid JSON: %s", r.reason);
      send_error(call.out, 400, message, call.options);
      return Outcome::kDone;
    case command::SetResult::kInvalid:
      if (!r.listed) {  // a set-up step's refusal: one reason
        std::snprintf(message, sizeof message, "nothing changed: %s", r.reason);
        send_error(call.out, refused_status, message, call.options);
        return Outcome::kDone;
      }
      send_json(call.out, 422, call.options, [&](JsonWriter& w) {
        w.begin_object().member("error", r.reason).key("errors").begin_object();
        for (std::size_t n = 0; n < errors_.size(); ++n)
          w.member(errors_[n].key, errors_[n].reason);
        w.end_object().end_object();
      });
      return Outcome::kDone;
    case command::SetResult::kNotSaved:
      send_error(call.out, 500, "the settings could not be saved; nothing was changed",
                 call.options);
      return Outcome::kDone;
    case command::SetResult::kOk:
      break;
  }
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object().member("ok", true).member("saved", ctx_.storage != nullptr);
    w.key("changed").begin_array();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (r.changed[n]) w.string(settings::def(static_cast<Id>(n)).key);
    w.end_array().key("restart_required").begin_array();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (r.changed[n] && (settings::def(static_cast<Id>(n)).flags & settings::kRestart))
        w.string(settings::def(static_cast<Id>(n)).key);
    w.end_array().end_object();
  });
  return Outcome::kDone;
}

bool Api::save() {
  if (ctx_.storage == nullptr) return true;
  // Only the user's layer over the defaults is stored (settings_layers.hpp).
  // scratch_ is free again here: post and reset are done with it.
  if (ctx_.defaults == nullptr) scratch_.reset_to_defaults();
  const settings::Settings& base = ctx_.defaults != nullptr ? *ctx_.defaults : scratch_;
  return save_settings(*ctx_.storage, ctx_.controller.settings(), base, document_,
                       sizeof(document_));
}

bool Api::persist(protocol::ByteSink& out, const ResponseOptions& options) {
  if (save()) return true;
  send_error(out, 500, "the settings could not be saved; nothing was changed", options);
  return false;
}

}  // namespace rotord::web
