#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "util/error.hpp"

namespace rotord::settings {

/// kText: a string kept in fixed storage inside Settings (no heap, so the
/// Cortex-M0+ core can copy a Settings like plain data). Its row reuses the
/// numeric columns: min/max are the length limits in bytes of a non-empty
/// value (empty is always allowed at row level: "not set"), unit names the
/// format (TextFormat), choices holds the default text.
enum class Type : std::uint8_t { kFloat, kInt, kBool, kEnum, kText };

/// kSecret (text only): never reported back. Readers (GET /api/settings, the
/// export, protocol get commands) see kSecretMask when a value is stored and
/// "" when not; writing kSecretMask keeps the stored value, so a document read
/// from the API can be written back without wiping the secret.
/// kWebOnly: written only through the web page and the REST API (behind
/// the login when access control is on), never through a line protocol; the
/// access rules themselves, so a client cannot widen its own rights.
/// kHidden: not a field of the settings form; an endpoint of its own sets it
/// (the web password through POST /api/password, tokens through
/// /api/tokens), because the stored value is a hash, not what the user types.
/// kAdvanced: rarely changed; the settings form keeps it under "Advanced".
enum Flags : std::uint8_t {
  kNone = 0,
  kRestart = 1,
  kSecret = 2,
  kWebOnly = 4,
  kHidden = 8,
  kAdvanced = 16
};

inline constexpr const char* kSecretMask = "********";

enum class Id : std::uint16_t {
#define SETTING(id, ...) id,
#include "settings/settings_table.def"
#undef SETTING
  kCount
};

inline constexpr std::size_t kCount = static_cast<std::size_t>(Id::kCount);

namespace detail {
/// Bytes of text storage per row (max length + NUL for kText, 0 otherwise).
inline constexpr std::size_t kTextBytesOf[] = {
#define SETTING(id, key, type, unit, min, max, ...) \
  (Type::type == Type::kText ? static_cast<std::size_t>(max) + 1 : 0),
#include "settings/settings_table.def"
#undef SETTING
};
/// Where each row's text starts in Settings' text storage.
inline constexpr auto kTextOffset = [] {
  std::array<std::size_t, kCount + 1> offset{};
  for (std::size_t n = 0; n < kCount; ++n) offset[n + 1] = offset[n] + kTextBytesOf[n];
  return offset;
}();
}  // namespace detail

/// All text settings together, NUL terminators included.
inline constexpr std::size_t kTextBytes = detail::kTextOffset[kCount];
/// The longest text setting, in bytes (without the NUL).
inline constexpr std::size_t kMaxTextBytes = [] {
  std::size_t longest = 1;
  for (std::size_t bytes : detail::kTextBytesOf) longest = bytes > longest ? bytes : longest;
  return longest - 1;
}();
/// A buffer that holds any value format_value writes, with its NUL: the
/// longest text, or a number, boolean or choice name (well under 48).
inline constexpr std::size_t kValueTextCapacity = kMaxTextBytes + 1 > 48 ? kMaxTextBytes + 1 : 48;

/// What a text setting may hold, named in its row's unit column.
enum class TextFormat : std::uint8_t {
  kText,          ///< "": UTF-8 without control characters (an SSID)
  kAscii,         ///< "ascii": printable ASCII (a WPA2 passphrase)
  kIpv4,          ///< "ipv4": dotted quad, 0-255 each, no leading zeros
  kLabel,         ///< "label": one DNS label (letters, digits, '-'), a host name without domain
  kHostname,      ///< "hostname": dotted DNS labels, or a dotted quad
  kHostList,      ///< "hostlist": host names separated by commas or spaces
  kNetworks,      ///< "networks": IPv4 networks (a.b.c.d/n) or addresses, comma or space separated
  kPasswordHash,  ///< "pwhash": a stored web password hash (access/password_hash.hpp)
  kTokenRecord,   ///< "token": a stored REST token record (access/api_token.hpp)
  kPreset,        ///< "preset": a named heading, <az_deg>[L]:<name> (settings/preset.hpp)
};

/// One row of the settings table. The order of the members packs the two
/// bytes and the label into what was padding before the doubles on the
/// Cortex-M0+, so the labels cost the firmware their text only.
struct Def {
  const char* key;
  Type type;
  std::uint8_t flags;
  std::uint8_t condition;  ///< index of the row's condition (condition())
  const char* unit;
  const char* label;  ///< the setting in the owner's words ("Slow zone before the target")
  double min;
  double max;
  double default_value;
  const char* group;    ///< one of groups(), as an owner thinks of it
  const char* choices;  ///< enum names separated by '|'; kText: the default text
  // The help column is not compiled in: the web UI serves it gzipped
  // (settings_help.js, generated from the table by web/tools/settings_help.mjs).
};

const Def& def(Id id);
/// The groups of the settings form in the order an owner meets them
/// (Rotator, Wiring, Calibration, ...); every row's group is one of them.
std::span<const char* const> groups();
/// When the row applies ("" always): terms joined by '&', all of which must
/// hold, alternatives joined by ';'. A term is a key (a bool that is on, a
/// number that is not 0, a text that is not empty) or key=choice|choice (an
/// enum set to one of them);
/// the key "platform" is the firmware's (pico_w, gpiod, sim: applies.hpp).
/// The settings form hides a row whose condition does not hold.
std::string_view condition(Id id);
TextFormat text_format(Id id);
std::optional<Id> find(std::string_view key);

/// The number of choices of an enum setting and the name of one of them.
int choice_count(Id id);
std::string_view choice_name(Id id, int index);

inline bool is_text(Id id) {
  return def(id).type == Type::kText;
}
inline bool is_secret(Id id) {
  return (def(id).flags & kSecret) != 0;
}
/// The access rules and the credentials (the "Access" group, and
/// mqtt.control, which lets the broker command): when one of them cannot be
/// read from the stored settings, the controller fails closed.
bool is_access_rule(Id id);

/// Whether a line protocol (rotctld `C`, Easycomm `CW`) may write the row:
/// not secrets, not the access rules.
inline bool line_writable(Id id) {
  return (def(id).flags & (kSecret | kWebOnly)) == 0;
}

/// Result of a rejected value, with a human-readable reason for forms and
/// protocol errors.
struct Rejection {
  Error error = Error::kOk;
  const char* reason = "";
};

/// The values of every setting. Plain data (an array of doubles and the fixed
/// text storage), so a copy is cheap and the controller can compare a
/// candidate set before applying it.
class Settings {
 public:
  Settings();

  /// Numeric settings (text settings read 0: use text()).
  double get(Id id) const { return values_[static_cast<std::size_t>(id)]; }
  /// A text setting's stored value (secrets unmasked: for the port's use
  /// only, never for a reply); empty for numeric settings.
  std::string_view text(Id id) const;
  float f(Id id) const { return static_cast<float>(get(id)); }
  int i(Id id) const { return static_cast<int>(get(id)); }
  bool b(Id id) const { return get(id) != 0.0; }

  /// Sets a value after checking type and range; nothing changes on error.
  /// Text settings refuse this (use set_text).
  Rejection set(Id id, double value);
  /// Sets a text setting after checking length and format. A secret given as
  /// kSecretMask keeps its stored value.
  Rejection set_text(Id id, std::string_view value);
  /// Parses text the way every front end sends it: numbers ("12.5", "-3"),
  /// booleans ("true"/"false"/"1"/"0"), enum names or indices, text as is
  /// (not trimmed: spaces count in an SSID or a password).
  Rejection set_from_text(Id id, std::string_view text);
  /// set_from_text followed by check_consistency; a value that breaks a
  /// cross-setting rule is undone (the protocols' single-key writes).
  Rejection update_from_text(Id id, std::string_view text);
  /// Whether `id` holds the same value here and in `other`.
  bool same_value(Id id, const Settings& other) const;
  /// Copies one value from a Settings that was validated already.
  void copy_value(Id id, const Settings& from);
  /// Formats the current value for text protocols ("12.5", "true", "relay",
  /// the text; kSecretMask or "" for a secret).
  std::size_t format_value(Id id, char* out, std::size_t capacity) const;
  /// What a reader may see of a text setting: the text, or for a secret
  /// kSecretMask when set and "" when empty.
  std::string_view visible_text(Id id) const;
  /// Checks the rules that span several settings (min below max, two
  /// distinct calibration points, no two functions on one pin...). A reason
  /// that names values (pin conflicts) points into this object and stays
  /// valid until the next check on it.
  Rejection check_consistency() const;
  /// The rules a value must meet when someone saves it, on top of
  /// check_consistency (settings_dependent.cpp): the park position within
  /// the travel, each slow zone shorter than its travel. Checked only for a
  /// rule one of whose settings differs from `before` (or is `changed`), so
  /// a save is judged by what it changes; never by the file loader, which
  /// must keep a station running on what it stored.
  Rejection check_dependent(const Settings& before) const;
  Rejection check_dependent(Id changed) const;
  /// update_from_text, then check_dependent: a protocol's write of one key.
  Rejection save_from_text(Id id, std::string_view text);

  void reset_to_defaults();

  /// The access settings (is_access_rule) could not be read at start-up
  /// (json/settings_load.hpp): the controller fails closed. Every network
  /// and line client is then read-only (STOP and status only: may_control,
  /// the web API, the MQTT commands), nobody is on the allow-list, until the
  /// owner fixes the stored settings and restarts. Not a setting: never
  /// stored, and only load_settings sets it.
  bool access_unreadable() const { return access_unreadable_; }
  void set_access_unreadable(bool unreadable) { access_unreadable_ = unreadable; }

  /// Bumps on every change; the controller re-derives its configuration when it moves.
  std::uint32_t revision() const { return revision_; }

  /// Formats a value for text protocols and files ("12.5", "true", "relay").
  static std::size_t format(Id id, double value, char* out, std::size_t capacity);

 private:
  Rejection check_network() const;
  /// One rule of check_dependent applies when `touched` says one of its
  /// settings changed.
  template <typename Touched>
  Rejection check_dependent_rules(Touched touched) const;
  char* text_slot(Id id) { return text_ + detail::kTextOffset[static_cast<std::size_t>(id)]; }
  const char* text_slot(Id id) const {
    return text_ + detail::kTextOffset[static_cast<std::size_t>(id)];
  }

  double values_[kCount];
  char text_[kTextBytes > 0 ? kTextBytes : 1] = {};
  std::uint32_t revision_ = 0;
  bool access_unreadable_ = false;
  // The text of the last rule that names keys and values, e.g. "pins.btn_cw
  // and pins.az_ma3 both use GPIO 2" (the core has no mutable globals).
  mutable char detail_[160] = {};
};

/// Checks a value against a row without storing it.
Rejection validate(Id id, double value);
/// Checks a text against a text row (length, format) without storing it.
Rejection validate_text(Id id, std::string_view value);
/// Parses a dotted quad ("192.168.1.20") strictly: four numbers 0-255, no
/// leading zeros, nothing else. `out` is host order (192.168.1.20 = 0xC0A80114).
bool parse_ipv4(std::string_view text, std::uint32_t& out);

}  // namespace rotord::settings
