#include "command/settings_commands.hpp"

#include <cstring>

namespace rotord::command {
namespace {

using settings::Id;

/// The keys of a log line, cut with "..." where they would not fit the
/// line (command_log.cpp writes at most 176 bytes).
constexpr std::size_t kKeysBytes = 100;
std::string_view key_list(const web::SettingSet& keys, char (&text)[kKeysBytes]) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < settings::kCount; ++i) {
    if (!keys[i]) continue;
    std::string_view part = settings::def(static_cast<Id>(i)).key;
    if (n + 1 + part.size() + 4 > sizeof text) part = "...";  // room for " ..." is kept
    if (n > 0) text[n++] = ' ';
    std::memcpy(text + n, part.data(), part.size());
    n += part.size();
    if (part == "...") break;
  }
  return {text, n};
}

/// Writes the line of "set" (or `what`) over `keys`; returns `result`.
SetResult told_set(Controller& controller, const Origin& from, const SetResult& result,
                   const web::SettingSet& keys, std::string_view what = "set") {
  char text[kKeysBytes];
  told(controller, from, what, outcome_word(result), NAN, NAN, key_list(keys, text));
  return result;
}

web::SettingSet one(Id id) {
  web::SettingSet keys;
  keys[static_cast<std::size_t>(id)] = true;
  return keys;
}

}  // namespace

Writer line_writer(const access::Peer& peer) {
  return peer.kind == access::Peer::Kind::kLine ? Writer::kLine : Writer::kNetwork;
}

Refusal may_write(Id id, Writer writer) {
  const auto flags = settings::def(id).flags;
  switch (writer) {
    case Writer::kLogin:
      return Refusal::kNone;
    case Writer::kToken:
      return settings::line_writable(id) ? Refusal::kNone : Refusal::kLogin;
    default:
      if ((flags & (settings::kWebOnly | settings::kHidden)) != 0) return Refusal::kWebOnly;
      if ((flags & settings::kSecret) != 0 && writer == Writer::kNetwork) return Refusal::kPassword;
      return Refusal::kNone;
  }
}

std::string_view outcome_word(const SetResult& result) {
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
                      std::string_view text) {
  SetResult result;
  result.key = id;
  result.refusal = may_write(id, writer);
  if (result.refusal != Refusal::kNone) {
    result.status = SetResult::kRefused;
  } else if (const settings::Rejection r = controller.settings().save_from_text(id, text);
             r.error != Error::kOk) {
    result.status = SetResult::kInvalid;
    result.reason = r.reason;
  }
  return told_set(controller, from, result, one(id));
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
      if (!id || may_write(*id, writer) == Refusal::kNone) continue;
      result.status = SetResult::kRefused;
      result.refusal = may_write(*id, writer);
      result.key = *id;
      return told_set(controller, from, result, one(*id));
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
    web::SettingSet keys;
    for (std::size_t n = 0; n < scratch.errors.size(); ++n)
      if (const std::optional<Id> id = settings::find(scratch.errors[n].key))
        keys[static_cast<std::size_t>(*id)] = true;
    return told_set(controller, from, result, keys);
  }
  result = keep_change(controller, store);
  if (store == nullptr) result.changed = r.changed;
  return told_set(controller, from, result, r.named);
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
  told(controller, from, "reset", outcome_word(result), NAN, NAN, "settings");
  return result;
}

SetResult keep_change(Controller& controller, const Store* store) {
  SetResult result;
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
