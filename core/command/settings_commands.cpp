#include "command/settings_commands.hpp"

#include <cstdio>

namespace rotord::command {
namespace {

using settings::Id;

/// The keys of a log line, cut at kKeysBytes (command_log.cpp writes at
/// most 176 bytes a line).
constexpr std::size_t kKeysBytes = 100;
const char* key_list(const web::SettingSet& keys, char (&text)[kKeysBytes]) {
  int n = 0;
  text[0] = '\0';
  for (std::size_t i = 0; i < settings::kCount; ++i)
    if (keys[i] && n < static_cast<int>(sizeof text))
      n += std::snprintf(text + n, sizeof text - n, n > 0 ? " %s" : "%s",
                         settings::def(static_cast<Id>(i)).key);
  return text;
}

}  // namespace

void told_words(Controller& controller, const Origin& from, const char* what, const char* outcome,
                const char* args) {
  told(controller, from, what, outcome, NAN, NAN, args);
}

Refusal may_write(Id id, Writer writer) {
  const auto flags = settings::def(id).flags;
  if (writer == Writer::kLogin) return Refusal::kNone;
  // A token: settings::line_writable's rule (not a secret, not web-only).
  if (writer == Writer::kToken)
    return (flags & (settings::kSecret | settings::kWebOnly)) != 0 ? Refusal::kLogin
                                                                   : Refusal::kNone;
  if ((flags & (settings::kWebOnly | settings::kHidden)) != 0) return Refusal::kWebOnly;
  return (flags & settings::kSecret) != 0 && writer == Writer::kNetwork ? Refusal::kPassword
                                                                        : Refusal::kNone;
}

const char* outcome_word(const SetResult& result) {
  switch (result.status) {
    case SetResult::kOk:
      return "OK";
    case SetResult::kRefused:
      return "DENIED";
    case SetResult::kNotSaved:
      return error_name(Error::kStorage);
    default:  // a value, or the document, the checks refused
      return error_name(Error::kInvalidArgument);
  }
}

SetResult set_setting(Controller& controller, const Origin& from, Writer writer, Id id,
                      std::string_view text, const Store* store) {
  SetResult result;
  result.refusal = may_write(id, writer);
  if (result.refusal != Refusal::kNone) {
    result.status = SetResult::kRefused;
  } else {
    if (store != nullptr) store->backup = controller.settings();
    result = keep_change(controller, store, controller.settings().save_from_text(id, text));
  }
  told_words(controller, from, "set", outcome_word(result), settings::def(id).key);
  return result;
}

SetResult set_settings(Controller& controller, const Origin& from, Writer writer,
                       std::string_view json, const Scratch& scratch, const Store* store) {
  SetResult result;
  if (writer != Writer::kLogin) {
    web::JsonObjectReader reader(json);
    std::string_view key;
    web::JsonValue value;
    while (reader.valid() && reader.next(key, value)) {
      const std::optional<Id> id = settings::find(key);
      if (!id || (result.refusal = may_write(*id, writer)) == Refusal::kNone) continue;
      result.status = SetResult::kRefused;
      result.key = *id;
      told_words(controller, from, "set", outcome_word(result), settings::def(*id).key);
      return result;
    }
  }
  settings::Settings& values = controller.settings();
  if (store != nullptr) store->backup = values;
  const web::ApplyOutcome r =
      web::apply_settings_json(json, values, scratch.settings, scratch.errors, true);
  if (r.status != web::ApplyOutcome::kApplied) {
    result.status =
        r.status == web::ApplyOutcome::kBadJson ? SetResult::kBadJson : SetResult::kInvalid;
    result.reason = r.message;
    result.listed = true;
    // The first key refused names the line (a rule across settings: none).
    told_words(controller, from, "set", outcome_word(result),
               scratch.errors.size() > 0 ? scratch.errors[0].key : "");
    return result;
  }
  result = keep_change(controller, store);
  result.changed = r.changed;  // with a store too: the same set
  char text[kKeysBytes];
  told_words(controller, from, "set", outcome_word(result), key_list(r.named, text));
  return result;
}

SetResult reset_settings(Controller& controller, const Origin& from,
                         const settings::Settings& defaults, const Store& store) {
  settings::Settings& values = controller.settings();
  store.backup = values;
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    // The web password and the tokens stay (POST /api/password with ""
    // opens the controller, on purpose).
    if ((settings::def(id).flags & settings::kHidden) == 0) values.copy_value(id, defaults);
  }
  const SetResult result = keep_change(controller, &store);
  told_words(controller, from, "reset", outcome_word(result), "settings");
  return result;
}

SetResult keep_change(Controller& controller, const Store* store,
                      const settings::Rejection& refused) {
  SetResult result;
  if (refused.error != Error::kOk) {
    result.status = SetResult::kInvalid;
    result.reason = refused.reason;
    return result;
  }
  if (store == nullptr) return result;
  settings::Settings& values = controller.settings();
  for (std::size_t n = 0; n < settings::kCount; ++n)
    result.changed[n] = !values.same_value(static_cast<Id>(n), store->backup);
  if (result.changed.none() || store->save(store->context)) return result;
  for (std::size_t n = 0; n < settings::kCount; ++n)
    if (result.changed[n]) values.copy_value(static_cast<Id>(n), store->backup);
  result.status = SetResult::kNotSaved;
  return result;
}

}  // namespace rotord::command
