// Reading the stored settings at start-up: every valid value is kept, only the
// bad ones are dropped and named, and a document whose access settings cannot
// be read makes the controller fail closed (docs/security.md, "Fail closed").
#include <cstdio>
#include <cstring>

#include "json/settings_json.hpp"
#include "json/settings_member.hpp"

namespace rotord::web {
namespace {

using settings::Id;

/// A key the table does not know that may have been meant as an access rule
/// (a hand-edited "access.control_network"): dropping it could leave the
/// controller more open than the owner meant, so it counts as one.
bool looks_like_access_rule(std::string_view key) {
  return key.starts_with("access.") || key.starts_with("web.") || key.starts_with("mqtt.control");
}

/// The readable part of a document with a syntax error (a torn write, a
/// damaged byte): everything up to the last whole member before the error,
/// closed with '}' in place. Empty when no member before it reads.
std::string_view readable_prefix(char* buf, std::size_t length, std::size_t error_at) {
  // Each try parses the prefix again: bounded, so a large damaged file costs
  // a few ms at start-up, never more.
  int tries = 64;
  for (std::size_t at = error_at < length ? error_at : length; at > 0 && tries > 0; --at) {
    if (buf[at - 1] != ',') continue;
    --tries;
    buf[at - 1] = '}';
    const std::string_view prefix(buf, at);
    if (JsonObjectReader(prefix).valid()) return prefix;
    buf[at - 1] = ',';
  }
  return {};
}

/// Applies the members of a valid document one by one: each good value
/// lands in `target`, each bad one is named in `report` and left at
/// `target`'s value. Then the rules across settings: the members a broken
/// rule names are dropped (or, when it names none of them, the members from
/// the end of the table) until the values agree. Returns the members kept;
/// `access_bad` when an access setting was dropped.
settings::KeySet apply_valid_members(std::string_view document, settings::Settings& target,
                                     settings::Settings& scratch, LoadReport& report,
                                     bool& access_bad) {
  JsonObjectReader reader(document);
  scratch = target;
  settings::KeySet kept;
  settings::KeySet twice;
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    if (key == settings::kVersionKey) continue;  // checked by the caller
    const auto id = settings::find(key);
    if (!id) {
      report.add(key, "unknown setting");
      access_bad = access_bad || looks_like_access_rule(key);
      continue;
    }
    const auto n = static_cast<std::size_t>(*id);
    if (kept[n] || twice[n]) {
      // Which of the two was meant is unknown: neither is kept.
      if (!twice[n]) report.add(key, "given twice");
      twice[n] = true;
      kept[n] = false;
      scratch.copy_value(*id, target);
      access_bad = access_bad || settings::is_access_rule(*id);
      continue;
    }
    if (const char* reason = detail::apply_member(*id, value, scratch)) {
      report.add(key, reason);
      access_bad = access_bad || settings::is_access_rule(*id);
      continue;
    }
    kept[n] = true;
  }
  for (std::size_t round = 0; round <= settings::kCount; ++round) {
    const settings::Rejection rule = scratch.check_consistency();
    if (rule.error == Error::kOk) break;
    // The reason may live in scratch, which the next check rewrites.
    char why[sizeof LoadReport::Entry::reason];
    std::snprintf(why, sizeof why, "%s", rule.reason);
    bool dropped = false;
    for (std::size_t n = 0; n < settings::kCount; ++n) {
      const auto id = static_cast<Id>(n);
      if (!kept[n] || std::strstr(why, settings::def(id).key) == nullptr) continue;
      report.add(settings::def(id).key, why);
      kept[n] = false;
      scratch.copy_value(id, target);
      access_bad = access_bad || settings::is_access_rule(id);
      dropped = true;
    }
    for (std::size_t n = settings::kCount; n > 0 && !dropped; --n) {
      const auto id = static_cast<Id>(n - 1);
      if (!kept[n - 1]) continue;
      report.add(settings::def(id).key, why);
      kept[n - 1] = false;
      scratch.copy_value(id, target);
      access_bad = access_bad || settings::is_access_rule(id);
      dropped = true;
    }
    if (!dropped) break;  // only the base is left, and the base agrees
  }
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    if (kept[n]) target.copy_value(static_cast<Id>(n), scratch);
  }
  return kept;
}

}  // namespace

void LoadReport::add(std::string_view key, std::string_view reason) {
  if (count_ == kMax) {
    ++more_;
    return;
  }
  Entry& e = entries_[count_++];
  std::snprintf(e.key, sizeof e.key, "%.*s", static_cast<int>(key.size()), key.data());
  std::snprintf(e.reason, sizeof e.reason, "%.*s", static_cast<int>(reason.size()), reason.data());
}

LoadOutcome load_settings(hal::Storage& storage, const settings::Settings& base,
                          LegacyBaseGuess* guess, settings::Settings& target,
                          settings::Settings& scratch, char* buf, std::size_t capacity,
                          LoadReport* report) {
  LoadOutcome outcome;
  LoadReport local;
  LoadReport& problems = report != nullptr ? *report : local;
  problems.clear();
  target = base;
  target.set_access_unreadable(false);
  // Nothing readable although something is stored: the base, failed closed.
  const auto corrupt = [&](const char* key, const char* reason) {
    target = base;
    target.set_access_unreadable(true);
    problems.add(key, reason);
    problems.access_unreadable = true;
    outcome.status = LoadOutcome::kCorrupt;
    outcome.reason = reason;
    outcome.access_unreadable = true;
    std::snprintf(outcome.key, sizeof outcome.key, "%s", key);
    return outcome;
  };
  const long n = storage.load(buf, capacity);
  if (n == -1) return outcome;
  if (n < 0 || static_cast<std::size_t>(n) > capacity)
    return corrupt("", "the stored settings cannot be read or are too large");
  std::string_view document(buf, static_cast<std::size_t>(n));
  bool access_bad = false;
  {
    const JsonObjectReader whole(document);
    if (!whole.valid()) {
      document = readable_prefix(buf, document.size(), whole.error_offset());
      if (document.empty()) return corrupt("", whole.error());
      // What followed the damage may have held access settings.
      char why[sizeof LoadReport::Entry::reason];
      std::snprintf(why, sizeof why, "the file is damaged or cut short (%s): read up to byte %zu",
                    whole.error(), document.size() - 1);
      problems.add("", why);
      access_bad = true;
    }
  }
  // A file from a newer rotord may mean other things by the same keys: none
  // of it is taken.
  {
    JsonObjectReader reader(document);
    std::string_view key;
    JsonValue value;
    int version = 0;
    while (reader.next(key, value)) {
      if (key != settings::kVersionKey) continue;
      if (const char* reason = detail::read_version(value, version))
        return corrupt(settings::kVersionKey, reason);
    }
  }
  // A version-1 file holds every setting as it was in force, profile values
  // included: read it over the table's defaults, and keep as the user's what
  // differs from the base it was saved over. A version-2 file is the user's
  // layer itself, checked over the base it now sits on.
  const bool legacy = detail::stored_version(document) < settings::kStoredVersion;
  if (legacy) target.reset_to_defaults();
  const settings::KeySet named =
      apply_valid_members(document, target, scratch, problems, access_bad);
  if (legacy) {
    const settings::Settings& saved_over = guess != nullptr ? guess->base_of(target) : base;
    const settings::KeySet keys = named & settings::user_layer(target, saved_over);
    const settings::Rejection rule =
        settings::apply_user_layer(base, target, keys, scratch, target);
    if (rule.error != Error::kOk) return corrupt("", rule.reason);
    outcome.migrated = true;
  }
  outcome.status =
      problems.size() > 0 || problems.more() > 0 ? LoadOutcome::kRepaired : LoadOutcome::kLoaded;
  if (outcome.status == LoadOutcome::kRepaired) {
    outcome.reason = "some values were dropped";
    std::snprintf(outcome.key, sizeof outcome.key, "%s", problems[0].key);
  }
  problems.access_unreadable = access_bad;
  outcome.access_unreadable = access_bad;
  target.set_access_unreadable(access_bad);
  return outcome;
}

}  // namespace rotord::web
