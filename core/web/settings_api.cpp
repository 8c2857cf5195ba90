// The settings over REST: GET/POST /api/settings, POST /api/settings/reset,
// and saving them (docs/web_api.md, "Settings").
#include <cstdio>

#include "json/json_reader.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

using settings::Id;

void Api::get_settings(protocol::ByteSink& out, const ResponseOptions& options) {
  const settings::Settings& values = ctx_.controller.settings();
  send_json(out, 200, options, [&](JsonWriter& w) { write_settings(values, w); });
}

void Api::post_settings(std::string_view body, protocol::ByteSink& out,
                        const ResponseOptions& options, const Caller& caller) {
  settings::Settings& values = ctx_.controller.settings();
  if (WebAuth::enabled(values) && !caller.may_administer()) {
    // A control token changes the rotator's settings, never the access
    // rules or a secret: it cannot widen its own rights.
    JsonObjectReader reader(body);
    std::string_view key;
    JsonValue value;
    while (reader.valid() && reader.next(key, value)) {
      const std::optional<Id> id = settings::find(key);
      if (id && !settings::line_writable(*id)) {
        count_auth_failure(false);
        char message[128];
        std::snprintf(message, sizeof message, "%s needs the web login, not a token",
                      settings::def(*id).key);
        send_error(out, 403, message, options);
        return;
      }
    }
  }
  backup_ = values;
  const ApplyOutcome r = apply_settings_json(body, values, scratch_, errors_, true);
  if (r.status == ApplyOutcome::kBadJson) {
    char message[160];
    std::snprintf(message, sizeof(message), "invalid JSON: %s", r.message);
    send_error(out, 400, message, options);
    return;
  }
  if (r.status == ApplyOutcome::kInvalid) {
    send_json(out, 422, options, [&](JsonWriter& w) {
      w.begin_object().member("error", r.message).key("errors").begin_object();
      for (std::size_t n = 0; n < errors_.size(); ++n) w.member(errors_[n].key, errors_[n].reason);
      w.end_object().end_object();
    });
    return;
  }
  save_changed(out, options, r.changed);
}

void Api::reset_settings(protocol::ByteSink& out, const ResponseOptions& options) {
  settings::Settings& values = ctx_.controller.settings();
  if (ctx_.defaults != nullptr) {
    scratch_ = *ctx_.defaults;
  } else {
    scratch_.reset_to_defaults();
  }
  const settings::Settings& defaults = scratch_;
  backup_ = values;
  SettingSet changed;
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    // The web password and the tokens stay: a reset must not open the
    // controller to everyone (POST /api/password with "" does that).
    if ((settings::def(id).flags & settings::kHidden) != 0) continue;
    if (!values.same_value(id, defaults)) {
      changed[n] = true;
      values.copy_value(id, defaults);
    }
  }
  save_changed(out, options, changed);
}

void Api::save_changed(protocol::ByteSink& out, const ResponseOptions& options,
                       const SettingSet& changed) {
  if (changed.any() && !persist(out, options)) {
    settings::Settings& values = ctx_.controller.settings();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (changed[n]) values.copy_value(static_cast<Id>(n), backup_);
    return;
  }
  send_changed(out, options, changed);
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

void Api::send_changed(protocol::ByteSink& out, const ResponseOptions& options,
                       const SettingSet& changed) {
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object().member("ok", true).member("saved", ctx_.storage != nullptr);
    w.key("changed").begin_array();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (changed[n]) w.string(settings::def(static_cast<Id>(n)).key);
    w.end_array().key("restart_required").begin_array();
    for (std::size_t n = 0; n < settings::kCount; ++n)
      if (changed[n] && (settings::def(static_cast<Id>(n)).flags & settings::kRestart))
        w.string(settings::def(static_cast<Id>(n)).key);
    w.end_array().end_object();
  });
}

}  // namespace rotord::web
