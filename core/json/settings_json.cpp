#include "json/settings_json.hpp"

#include <cstring>

#include "json/settings_member.hpp"
#include "util/fixed_sink.hpp"

namespace rotord::web {
namespace {

using settings::Id;
using settings::Type;

}  // namespace

namespace detail {

/// Checks one member against its row and stores it in `candidate`; returns
/// the reason on failure.
const char* apply_member(Id id, const JsonValue& v, settings::Settings& candidate) {
  const settings::Def& d = settings::def(id);
  double value = 0.0;
  switch (d.type) {
    case Type::kText: {
      if (v.type != JsonType::kString) return "expected a string";
      if (v.truncated) return "too long (see the maximum length)";
      const settings::Rejection r = candidate.set_text(id, v.text);
      return r.error == Error::kOk ? nullptr : r.reason;
    }
    case Type::kFloat:
    case Type::kInt:
      if (v.type != JsonType::kNumber) return "expected a number";
      value = v.number;
      break;
    case Type::kBool:
      if (v.type != JsonType::kBool) return "expected true or false";
      value = v.boolean ? 1.0 : 0.0;
      break;
    case Type::kEnum: {
      if (v.type != JsonType::kString) return "expected one of the choices (a string)";
      int found = -1;
      for (int n = 0; n < settings::choice_count(id); ++n)
        if (!v.truncated && settings::choice_name(id, n) == v.text) found = n;
      if (found < 0) return "not one of the choices";
      value = found;
      break;
    }
  }
  const settings::Rejection r = candidate.set(id, value);
  return r.error == Error::kOk ? nullptr : r.reason;
}

/// Reads settings::kVersionKey's value; the reason when it is not a version
/// this build reads.
const char* read_version(const JsonValue& v, int& version) {
  if (v.type != JsonType::kNumber || v.number != static_cast<int>(v.number) || v.number < 1)
    return "expected a whole number from 1";
  if (v.number > settings::kStoredVersion) return "written by a newer rotord";
  version = static_cast<int>(v.number);
  return nullptr;
}

/// The document's settings::kVersionKey, 1 when it has none (or is no
/// object: apply_settings_json then says why).
int stored_version(std::string_view json) {
  JsonObjectReader reader(json);
  std::string_view key;
  JsonValue value;
  while (reader.valid() && reader.next(key, value)) {
    if (key == settings::kVersionKey && value.type == JsonType::kNumber)
      return value.number >= settings::kStoredVersion ? settings::kStoredVersion : 1;
  }
  return 1;
}

}  // namespace detail

using detail::apply_member;
using detail::read_version;

void SettingErrors::add(std::string_view key, const char* reason) {
  if (count_ == kMax) {
    ++dropped_;
    return;
  }
  Entry& e = entries_[count_++];
  const std::size_t n = key.size() < sizeof(e.key) - 1 ? key.size() : sizeof(e.key) - 1;
  std::memcpy(e.key, key.data(), n);
  e.key[n] = '\0';
  e.reason = reason;
}

void write_setting_value(Id id, double value, JsonWriter& out) {
  switch (settings::def(id).type) {
    case Type::kBool:
      out.boolean(value != 0.0);
      break;
    case Type::kEnum:
      out.string(settings::choice_name(id, static_cast<int>(value)));
      break;
    case Type::kInt:
      out.integer(static_cast<long long>(value));
      break;
    case Type::kText:  // no text in a double: write_setting has it
      out.string("");
      break;
    case Type::kFloat: {
      // Settings::format writes the shortest text that reads back the same
      // (0.15, not 0.1500000059604645).
      char text[32];
      const std::size_t len = settings::Settings::format(id, value, text, sizeof(text));
      out.raw_value(std::string_view(text, len));
      break;
    }
  }
}

void write_setting(const settings::Settings& values, Id id, JsonWriter& out, Secrets secrets) {
  if (!settings::is_text(id)) {
    write_setting_value(id, values.get(id), out);
  } else {
    out.string(secrets == Secrets::kReveal ? values.text(id) : values.visible_text(id));
  }
}

void write_settings(const settings::Settings& values, JsonWriter& out, Secrets secrets) {
  out.begin_object();
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    out.key(settings::def(id).key);
    write_setting(values, id, out, secrets);
  }
  out.end_object();
  out.flush();
}

void write_settings_schema(const settings::Settings& defaults, JsonWriter& out,
                           std::string_view platform) {
  static constexpr const char* kTypeNames[] = {"float", "int", "bool", "enum", "text"};
  static constexpr const char* kFormatNames[] = {"text",     "ascii",    "ipv4",     "label",
                                                 "hostname", "hostlist", "networks", "pwhash",
                                                 "token",    "preset"};
  static_assert(sizeof(kFormatNames) / sizeof(kFormatNames[0]) ==
                    static_cast<std::size_t>(settings::TextFormat::kPreset) + 1,
                "a name for every text format");
  out.begin_object();
  // The form hides the rows whose condition does not hold on this platform.
  if (!platform.empty()) out.member("platform", platform);
  out.key("groups").begin_array();
  for (const char* group : settings::groups()) out.string(group);
  out.end_array().key("settings").begin_array();
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    const settings::Def& d = settings::def(id);
    const bool text = settings::is_text(id);
    out.begin_object()
        .member("key", d.key)
        .member("type", settings::is_secret(id) ? "password" : kTypeNames[static_cast<int>(d.type)])
        .member("unit", text ? "" : d.unit)
        .member("min", d.min)
        .member("max", d.max);
    if (text) out.member("format", kFormatNames[static_cast<int>(settings::text_format(id))]);
    out.key("default");
    write_setting(defaults, id, out);
    out.member("group", d.group).member("label", d.label);
    if (!settings::condition(id).empty()) out.member("when", settings::condition(id));
    if ((d.flags & settings::kAdvanced) != 0) out.member("advanced", true);
    out.key("choices").begin_array();
    for (int c = 0; c < settings::choice_count(id); ++c) out.string(settings::choice_name(id, c));
    out.end_array();
    out.member("restart", (d.flags & settings::kRestart) != 0);
    // Set through its own endpoint, not the form (settings::kHidden).
    if ((d.flags & settings::kHidden) != 0) out.member("hidden", true);
    out.end_object();
  }
  out.end_array().end_object();
  out.flush();
}

ApplyOutcome apply_settings_json(std::string_view json, settings::Settings& target,
                                 settings::Settings& scratch, SettingErrors& errors, bool saving) {
  ApplyOutcome outcome;
  errors.clear();
  JsonObjectReader reader(json);
  if (!reader.valid()) {
    outcome.status = ApplyOutcome::kBadJson;
    outcome.message = reader.error();
    return outcome;
  }
  scratch = target;
  SettingSet seen;
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    if (key == settings::kVersionKey) {
      if (const char* reason = read_version(value, outcome.version)) errors.add(key, reason);
      continue;
    }
    const auto id = settings::find(key);
    if (!id) {
      errors.add(key, "unknown setting");
      continue;
    }
    if (seen[static_cast<std::size_t>(*id)]) {
      errors.add(key, "given twice");
      continue;
    }
    seen[static_cast<std::size_t>(*id)] = true;
    if (const char* reason = apply_member(*id, value, scratch)) errors.add(key, reason);
  }
  if (errors.size() > 0 || errors.dropped() > 0) {
    outcome.status = ApplyOutcome::kInvalid;
    outcome.message = errors[0].reason;
    return outcome;
  }
  settings::Rejection rule = scratch.check_consistency();
  if (rule.error == Error::kOk && saving) rule = scratch.check_dependent(target);
  if (rule.error != Error::kOk) {
    // Attach the rule to every key it names that this document set, so a
    // form can show it next to the fields involved.
    for (std::size_t n = 0; n < settings::kCount; ++n) {
      const char* name = settings::def(static_cast<Id>(n)).key;
      if (seen[n] && std::strstr(rule.reason, name) != nullptr) errors.add(name, rule.reason);
    }
    outcome.status = ApplyOutcome::kInvalid;
    outcome.message = rule.reason;
    return outcome;
  }
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    if (!scratch.same_value(id, target)) {
      outcome.changed[n] = true;
      target.copy_value(id, scratch);  // validated above
    }
  }
  outcome.named = seen;
  return outcome;
}

bool save_settings(hal::Storage& storage, const settings::Settings& values,
                   const settings::Settings& base, char* buf, std::size_t capacity) {
  FixedSink sink(buf, capacity);
  {
    JsonWriter writer(sink);
    writer.set_pretty(storage.human_readable());
    writer.begin_object();
    writer.member(settings::kVersionKey, settings::kStoredVersion);
    const settings::KeySet keys = settings::user_layer(values, base);
    for (std::size_t n = 0; n < settings::kCount; ++n) {
      if (!keys[n]) continue;
      const auto id = static_cast<Id>(n);
      writer.key(settings::def(id).key);
      write_setting(values, id, writer, Secrets::kReveal);  // the device's own copy
    }
    writer.end_object();
    writer.flush();
  }
  sink.write("\n");
  if (sink.overflowed()) return false;
  return storage.save(sink.view());
}

}  // namespace rotord::web
