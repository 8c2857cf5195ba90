#pragma once
#include <bitset>
#include <cstddef>
#include <string_view>

#include "hal/storage.hpp"
#include "json/json_reader.hpp"
#include "json/json_writer.hpp"
#include "settings/settings.hpp"
#include "settings/settings_layers.hpp"

// The JSON codec layer (core/json, docs/architecture.md): below web and storage,
// which both read and write JSON. Its names stayed in rotord::web, where the
// codec began, so the web API, the ports and the tests spell them as before.
namespace rotord::web {

/// The settings as JSON: one flat object {"key": value} in table order, with
/// numbers as numbers, booleans as true/false and enum settings by choice
/// name. The same document is GET /api/settings (every setting in force),
/// the body of POST /api/settings (partial), the web page's export file and,
/// as the user's layer only (settings_layers.hpp), what hal::Storage keeps;
/// an exported file can be imported or dropped in as the config.
///
/// Secrets (settings::kSecret) appear as settings::kSecretMask ("" when
/// empty) unless `secrets` is kReveal, which only the stored document uses.
enum class Secrets : unsigned char { kMask, kReveal };
void write_settings(const settings::Settings& values, JsonWriter& out,
                    Secrets secrets = Secrets::kMask);

/// One setting's value in its JSON form, text included (masked as above).
void write_setting(const settings::Settings& values, settings::Id id, JsonWriter& out,
                   Secrets secrets = Secrets::kMask);

/// One value in its JSON form (number, true/false or the choice's name).
void write_setting_value(settings::Id id, double value, JsonWriter& out);

/// The settings table for forms: the platform the firmware drives
/// (settings::platform_name, left out when empty), the groups in the form's
/// order (settings::groups), then every row with key, type, unit, min, max,
/// default (taken from `defaults`), group, label, "when" (its condition,
/// left out when it always applies), "advanced" (when rarely changed),
/// choices and whether it needs a restart. The help sentences are the web
/// UI's asset /settings_help.js (generated from the same table). Text rows have type
/// "text" or "password" (secrets), min/max as lengths and a "format"
/// (text_format).
void write_settings_schema(const settings::Settings& defaults, JsonWriter& out,
                           std::string_view platform = {});

/// Per-key reasons a document was refused, in a fixed table (no heap).
class SettingErrors {
 public:
  static constexpr std::size_t kMax = 8;
  struct Entry {
    char key[JsonObjectReader::kMaxKeyBytes + 1];
    const char* reason;
  };
  void add(std::string_view key, const char* reason);
  void clear() { count_ = 0, dropped_ = 0; }
  std::size_t size() const { return count_; }
  const Entry& operator[](std::size_t i) const { return entries_[i]; }
  /// Errors past kMax, counted but not kept.
  std::size_t dropped() const { return dropped_; }

 private:
  Entry entries_[kMax];
  std::size_t count_ = 0;
  std::size_t dropped_ = 0;
};

using SettingSet = settings::KeySet;

struct ApplyOutcome {
  enum Status : unsigned char { kApplied, kBadJson, kInvalid } status = kApplied;
  /// kBadJson: the syntax error; kInvalid: the first reason (or the
  /// consistency rule that failed).
  const char* message = "";
  SettingSet changed;  ///< kApplied: the settings whose value changed
  SettingSet named;    ///< kApplied: the settings the document named
  /// settings::kVersionKey's value; 0 when the document has none. The key is
  /// accepted (a stored file may be imported) up to settings::kStoredVersion.
  int version = 0;
};

/// Applies a (partial) settings document all-or-nothing: every member is
/// checked (known key, type, range) on a copy, then the cross-setting rules;
/// only when all pass is `target` updated. `scratch` holds the copy so the
/// caller decides where its ~600 bytes live (not the Pico's small stack).
/// `saving`: a person saves these values (REST, the console), so the rules
/// between dependent values are checked too (Settings::check_dependent);
/// the file loader passes false.
ApplyOutcome apply_settings_json(std::string_view json, settings::Settings& target,
                                 settings::Settings& scratch, SettingErrors& errors,
                                 bool saving = false);

/// The stored settings document (pretty-printed), with room to grow: the
/// buffers that load, save or export it (web::Api, the Pico's boot buffer).
/// 7.5 KB since the 16 presets (issue 26); a flash slot holds 8 KB.
inline constexpr std::size_t kMaxSettingsDocumentBytes = 8192;

/// What start-up reading dropped from the stored document, for the log and
/// the settings page (GET /api/status "settings_load"). Fixed storage: the
/// Pico keeps one statically.
class LoadReport {
 public:
  static constexpr std::size_t kMax = 6;
  struct Entry {
    char key[41];     ///< the member's key (cut at 40 bytes), or "" for the whole file
    char reason[88];  ///< why it was dropped
  };
  void add(std::string_view key, std::string_view reason);
  void clear() { count_ = 0, more_ = 0, access_unreadable = false; }
  std::size_t size() const { return count_; }
  const Entry& operator[](std::size_t i) const { return entries_[i]; }
  /// Problems past kMax, counted but not kept.
  std::size_t more() const { return more_; }
  bool empty() const { return count_ == 0 && more_ == 0 && !access_unreadable; }

  /// The access settings (settings::is_access_rule) could not all be read:
  /// the controller fails closed (settings::Settings::access_unreadable).
  bool access_unreadable = false;

 private:
  Entry entries_[kMax];
  std::size_t count_ = 0;
  std::size_t more_ = 0;
};

/// The outcome of reading the stored document at start-up.
struct LoadOutcome {
  enum Status : unsigned char {
    kNothingStored,
    kLoaded,    ///< every value read
    kRepaired,  ///< the valid values read, the bad ones dropped (LoadReport names them)
    kCorrupt,   ///< nothing could be read: `target` holds the base
  } status = kNothingStored;
  const char* reason = "";                            ///< kRepaired, kCorrupt: the first problem
  char key[JsonObjectReader::kMaxKeyBytes + 1] = "";  ///< its key, if any
  bool migrated = false;  ///< a version-1 file (every setting in it) was read
  /// The access settings could not all be read (kCorrupt always: the
  /// document was there but unreadable): the controller fails closed, and
  /// `target` says so (settings::Settings::access_unreadable).
  bool access_unreadable = false;
};

/// Picks the base a version-1 file was saved over, from the values it holds:
/// its user's layer is what differs from that base. The Linux simulator
/// recognises the profile a file was written under; without a guess the
/// current base is taken, which keeps every value the file holds.
class LegacyBaseGuess {
 public:
  virtual ~LegacyBaseGuess() = default;
  virtual const settings::Settings& base_of(const settings::Settings& file_values) = 0;
};

/// Loads the stored user's layer over `base` into `target`
/// (json/settings_load.cpp). A version-1 document is read over the table's
/// defaults, and the settings it holds that differ from `guess`'s base (or
/// `base`) become the user's layer, so a migrated file loses no value the
/// user changed.
///
/// A damaged document fails closed, not open: every valid value is kept and
/// only the bad ones are dropped (a value out of range, an unknown key, a
/// wrong type, a key given twice, values that break a rule across settings,
/// the part of a truncated file after its last whole member), each named in
/// `report` when given. When an access setting is among them (or an unknown
/// key that looks like one, or nothing could be read at all), `target` is
/// marked access_unreadable. The caller reports it and must not overwrite
/// the stored copy on its own.
LoadOutcome load_settings(hal::Storage& storage, const settings::Settings& base,
                          LegacyBaseGuess* guess, settings::Settings& target,
                          settings::Settings& scratch, char* buf, std::size_t capacity,
                          LoadReport* report = nullptr);

/// Serialises the user's layer of `values` over `base` into buf (pretty, one
/// setting per line, secrets revealed, settings::kVersionKey first) and saves
/// it. False when it does not fit or the storage fails.
bool save_settings(hal::Storage& storage, const settings::Settings& values,
                   const settings::Settings& base, char* buf, std::size_t capacity);

}  // namespace rotord::web
