#include "settings/settings.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "access/api_token.hpp"
#include "access/password_hash.hpp"
#include "settings/axis_label.hpp"
#include "settings/gpiod_rules.hpp"
#include "settings/network_list.hpp"
#include "settings/pin_rules.hpp"
#include "settings/pot_table.hpp"
#include "settings/preset.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::settings {
namespace {

// Every row's condition (applies.hpp), for the constant evaluation below
// only: the table stores an index into the distinct conditions, one byte in
// what is padding anyway, instead of a pointer per row.
constexpr std::string_view kRowConditions[] = {
#define SETTING(id, key, type, unit, min, max, def, group, flags, choices, label, condition, help) \
  condition,
#include "settings/settings_table.def"
#undef SETTING
};

constexpr bool seen_before(std::size_t row) {
  for (std::size_t n = 0; n < row; ++n)
    if (kRowConditions[n] == kRowConditions[row]) return true;
  return false;
}

constexpr std::size_t kConditionCount = [] {
  std::size_t count = 0;
  for (std::size_t n = 0; n < kCount; ++n) count += seen_before(n) ? 0 : 1;
  return count;
}();
static_assert(kConditionCount <= 256, "a condition index is one byte");

constexpr auto kConditions = [] {
  std::array<std::string_view, kConditionCount> distinct{};
  std::size_t count = 0;
  for (std::size_t n = 0; n < kCount; ++n)
    if (!seen_before(n)) distinct[count++] = kRowConditions[n];
  return distinct;
}();

constexpr std::uint8_t condition_index(std::size_t row) {
  std::size_t n = 0;
  while (kConditions[n] != kRowConditions[row]) ++n;
  return static_cast<std::uint8_t>(n);
}

// clang-format off
constexpr Def kDefs[] = {
#define SETTING(id, key, type, unit, min, max, def, group, flags, choices, label, condition, help) \
  {key, Type::type, flags, condition_index(static_cast<std::size_t>(Id::id)), unit, label,      \
   min, max, def, group, choices},
#include "settings/settings_table.def"
#undef SETTING
};
// clang-format on
static_assert(sizeof(kDefs) / sizeof(kDefs[0]) == kCount);

// The groups in the order the settings form shows them (docs/settings.md).
constexpr const char* kGroups[] = {"Rotator",           "Wiring",  "Calibration",
                                   "Limits and safety", "Station", "Tracking",
                                   "Network",           "Access",  "Integrations"};

constexpr bool known_group(std::string_view group) {
  for (std::string_view g : kGroups)
    if (g == group) return true;
  return false;
}
constexpr bool every_group_known() {
  for (const Def& d : kDefs)
    if (!known_group(d.group)) return false;
  return true;
}
static_assert(every_group_known(), "a row's group is not in kGroups");

}  // namespace

const Def& def(Id id) {
  return kDefs[static_cast<std::size_t>(id)];
}

std::span<const char* const> groups() {
  return kGroups;
}

std::string_view condition(Id id) {
  return kConditions[def(id).condition];
}

std::optional<Id> find(std::string_view key) {
  for (std::size_t n = 0; n < kCount; ++n) {
    if (key == kDefs[n].key) return static_cast<Id>(n);
  }
  return std::nullopt;
}

bool is_access_rule(Id id) {
  return std::string_view(def(id).group) == "Access" || id == Id::kMqttControl;
}

int choice_count(Id id) {
  if (def(id).type != Type::kEnum) return 0;
  const char* choices = def(id).choices;
  if (*choices == '\0') return 0;
  int count = 1;
  for (const char* c = choices; *c; ++c)
    if (*c == '|') ++count;
  return count;
}

TextFormat text_format(Id id) {
  const std::string_view unit = def(id).unit;
  if (unit == "ascii") return TextFormat::kAscii;
  if (unit == "ipv4") return TextFormat::kIpv4;
  if (unit == "label") return TextFormat::kLabel;
  if (unit == "hostname") return TextFormat::kHostname;
  if (unit == "hostlist") return TextFormat::kHostList;
  if (unit == "networks") return TextFormat::kNetworks;
  if (unit == "pwhash") return TextFormat::kPasswordHash;
  if (unit == "token") return TextFormat::kTokenRecord;
  if (unit == "preset") return TextFormat::kPreset;
  return TextFormat::kText;
}

std::string_view choice_name(Id id, int index) {
  std::string_view rest = def(id).choices;
  for (int n = 0; n < index; ++n) {
    std::size_t bar = rest.find('|');
    if (bar == std::string_view::npos) return {};
    rest.remove_prefix(bar + 1);
  }
  return text::slice(rest, 0, rest.find('|'));
}

bool parse_ipv4(std::string_view text, std::uint32_t& out) {
  std::uint32_t address = 0;
  for (int part = 0; part < 4; ++part) {
    if (part > 0) {
      if (text.empty() || text[0] != '.') return false;
      text.remove_prefix(1);
    }
    std::size_t digits = 0;
    unsigned value = 0;
    while (digits < text.size() && digits < 4 && text[digits] >= '0' && text[digits] <= '9')
      value = value * 10 + static_cast<unsigned>(text[digits++] - '0');
    // "010" is octal to inet_aton but decimal to people: refuse the ambiguity.
    if (digits == 0 || digits > 3 || value > 255 || (digits > 1 && text[0] == '0')) return false;
    text.remove_prefix(digits);
    address = (address << 8) | value;
  }
  if (!text.empty()) return false;
  out = address;
  return true;
}

namespace {

bool is_label_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-';
}

/// One DNS label (RFC 1123): 1-63 letters, digits or '-', not at either end.
bool is_label(std::string_view label) {
  if (label.empty() || label.size() > 63 || label.front() == '-' || label.back() == '-')
    return false;
  for (char c : label)
    if (!is_label_char(c)) return false;
  return true;
}

/// Well-formed UTF-8 without control characters (an SSID as phones show it).
bool is_clean_utf8(std::string_view text) {
  for (std::size_t n = 0; n < text.size();) {
    const auto c = static_cast<unsigned char>(text[n]);
    std::size_t extra = 0;
    if (c < 0x20 || c == 0x7f) return false;
    if (c >= 0x80) {
      if (c >= 0xc2 && c <= 0xdf) {
        extra = 1;
      } else if (c >= 0xe0 && c <= 0xef) {
        extra = 2;
      } else if (c >= 0xf0 && c <= 0xf4) {
        extra = 3;
      } else {
        return false;
      }
      if (n + extra >= text.size()) return false;
      for (std::size_t k = 1; k <= extra; ++k)
        if ((static_cast<unsigned char>(text[n + k]) & 0xc0) != 0x80) return false;
    }
    n += 1 + extra;
  }
  return true;
}

}  // namespace

Rejection validate_text(Id id, std::string_view value) {
  const Def& d = def(id);
  if (d.type != Type::kText) return {Error::kInvalidArgument, "not a text setting"};
  if (value.empty()) return {};  // "not set"; rules that need a value are cross-setting
  if (value.size() > static_cast<std::size_t>(d.max))
    return {Error::kOutOfRange, "too long (see the maximum length)"};
  if (value.size() < static_cast<std::size_t>(d.min))
    return {Error::kOutOfRange, "too short (see the minimum length)"};
  switch (text_format(id)) {
    case TextFormat::kText:
      if (!is_clean_utf8(value))
        return {Error::kInvalidArgument, "control characters or invalid UTF-8"};
      break;
    case TextFormat::kAscii:
      for (char c : value)
        if (c < 0x20 || c > 0x7e)
          return {Error::kInvalidArgument, "only printable ASCII characters (space to ~)"};
      break;
    case TextFormat::kIpv4: {
      std::uint32_t ignored = 0;
      if (!parse_ipv4(value, ignored))
        return {Error::kInvalidArgument,
                "not an IPv4 address (four numbers 0-255 with dots, e.g. 192.168.1.20)"};
      break;
    }
    case TextFormat::kLabel:
      if (!is_label(value))
        return {Error::kInvalidArgument, "letters, digits and '-' only, not first or last"};
      break;
    case TextFormat::kHostname:
      if (!is_hostname(value))
        return {
            Error::kInvalidArgument,
            "not a host name (labels of letters, digits and '-' joined by dots) or IPv4 address"};
      break;
    case TextFormat::kHostList: {
      bool bad = false;
      for_each_list_item(value, [&bad](std::string_view name) { bad = bad || !is_hostname(name); });
      if (bad)
        return {Error::kInvalidArgument,
                "host names (letters, digits, '-' and dots) separated by commas or spaces"};
      break;
    }
    case TextFormat::kNetworks: {
      bool bad = false;
      for_each_list_item(value, [&bad](std::string_view item) {
        IpNetwork ignored;
        bad = bad || !parse_network(item, ignored);
      });
      if (bad)
        return {Error::kInvalidArgument,
                "networks such as 192.168.1.0/24 or fd00::/8, or addresses such as 10.0.0.5 or "
                "::1, separated by commas or spaces"};
      break;
    }
    case TextFormat::kPasswordHash: {
      access::PasswordHash ignored;
      if (!access::parse_password_hash(value, ignored))
        return {Error::kInvalidArgument,
                "not a stored password hash: set the password with POST /api/password (or "
                "on the settings page), or \"\" to turn access control off"};
      break;
    }
    case TextFormat::kPreset: {
      Preset ignored;
      if (const char* why = parse_preset(value, ignored)) return {Error::kInvalidArgument, why};
      break;
    }
    case TextFormat::kTokenRecord: {
      access::TokenRecord ignored;
      if (!access::parse_token_record(value, ignored))
        return {Error::kInvalidArgument,
                "not a stored token: make tokens with POST /api/tokens, or \"\" to revoke"};
      break;
    }
  }
  return {};
}

Rejection validate(Id id, double value) {
  const Def& d = def(id);
  if (d.type == Type::kText) return {Error::kInvalidArgument, "a text setting takes text"};
  if (!std::isfinite(value)) return {Error::kInvalidArgument, "not a number"};
  if (d.type != Type::kFloat && value != std::floor(value))
    return {Error::kInvalidArgument, "must be a whole number"};
  if (value < d.min || value > d.max) return {Error::kOutOfRange, "outside the allowed range"};
  return {};
}

Settings::Settings() {
  reset_to_defaults();
}

void Settings::reset_to_defaults() {
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    values_[n] = kDefs[n].type == Type::kText ? 0.0 : kDefs[n].default_value;
    if (kDefs[n].type != Type::kText) continue;
    // Defaults are checked by the table test; a too-long one is cut, not overrun.
    const std::size_t cap = detail::kTextBytesOf[n] - 1;
    std::strncpy(text_slot(id), kDefs[n].choices, cap);
    text_slot(id)[cap] = '\0';
  }
  ++revision_;
}

std::string_view Settings::text(Id id) const {
  return is_text(id) ? std::string_view(text_slot(id)) : std::string_view();
}

std::string_view Settings::visible_text(Id id) const {
  const std::string_view t = text(id);
  if (is_secret(id) && !t.empty()) return kSecretMask;
  return t;
}

Rejection Settings::set_text(Id id, std::string_view value) {
  if (is_secret(id) && value == kSecretMask) return {};  // the mask read back: keep
  const Rejection r = validate_text(id, value);
  if (r.error != Error::kOk) return r;
  if (value == text(id)) return {};
  char* slot = text_slot(id);
  if (!value.empty()) std::memcpy(slot, value.data(), value.size());  // data() may be null
  slot[value.size()] = '\0';
  ++revision_;
  return {};
}

bool Settings::same_value(Id id, const Settings& other) const {
  return is_text(id) ? text(id) == other.text(id) : get(id) == other.get(id);
}

void Settings::copy_value(Id id, const Settings& from) {
  if (same_value(id, from)) return;
  if (is_text(id)) {
    const std::size_t n = static_cast<std::size_t>(id);
    std::memcpy(text_slot(id), from.text_slot(id), detail::kTextBytesOf[n]);
  } else {
    values_[static_cast<std::size_t>(id)] = from.get(id);
  }
  ++revision_;
}

Rejection Settings::set(Id id, double value) {
  Rejection r = validate(id, value);
  if (r.error != Error::kOk) return r;
  double& slot = values_[static_cast<std::size_t>(id)];
  if (slot != value) {
    slot = value;
    ++revision_;
  }
  return {};
}

Rejection Settings::set_from_text(Id id, std::string_view text) {
  const Def& d = def(id);
  if (d.type == Type::kText) return set_text(id, text);
  text = text::trim(text);
  if (d.type == Type::kBool) {
    if (text == "true" || text == "on" || text == "1") return set(id, 1);
    if (text == "false" || text == "off" || text == "0") return set(id, 0);
    return {Error::kInvalidArgument, "expected true or false"};
  }
  if (d.type == Type::kEnum) {
    for (int n = 0; n < choice_count(id); ++n)
      if (choice_name(id, n) == text) return set(id, n);
  }
  double value = 0;
  if (!text::parse_double(text, value)) return {Error::kInvalidArgument, "not a number"};
  return set(id, value);
}

Rejection Settings::update_from_text(Id id, std::string_view text) {
  // The previous value, to undo a write that breaks a cross-setting rule: a
  // number or one text slot, on the stack (not a whole Settings copy).
  const double before = get(id);
  char before_text[kMaxTextBytes + 1];
  const std::string_view old = this->text(id);
  if (!old.empty()) std::memcpy(before_text, old.data(), old.size());  // data() may be null
  const Rejection r = set_from_text(id, text);
  if (r.error != Error::kOk) return r;
  const Rejection rule = check_consistency();
  if (rule.error == Error::kOk) return {};
  if (is_text(id)) {
    set_text(id, std::string_view(before_text, old.size()));
  } else {
    set(id, before);
  }
  return rule;
}

Rejection Settings::check_consistency() const {
  if (get(Id::kAzMinDeg) >= get(Id::kAzMaxDeg))
    return {Error::kOutOfRange, "az.min_deg must be below az.max_deg"};
  if (get(Id::kAzMaxDeg) - get(Id::kAzMinDeg) > 720)
    return {Error::kOutOfRange, "azimuth travel cannot exceed 720 deg"};
  if (get(Id::kElMinDeg) >= get(Id::kElMaxDeg))
    return {Error::kOutOfRange, "el.min_deg must be below el.max_deg"};
  if (get(Id::kAzPotCalLoCounts) == get(Id::kAzPotCalHiCounts) ||
      get(Id::kAzPotCalLoDeg) == get(Id::kAzPotCalHiDeg))
    return {Error::kOutOfRange, "the two azimuth calibration points must differ"};
  if (get(Id::kElPotCalLoCounts) == get(Id::kElPotCalHiCounts) ||
      get(Id::kElPotCalLoDeg) == get(Id::kElPotCalHiDeg))
    return {Error::kOutOfRange, "the two elevation calibration points must differ"};
  for (const AxisId axis : {AxisId::kAz, AxisId::kEl}) {
    const PotCalibration cal = pot_calibration_from(*this, axis);
    const int bad = cal.first_bad_point();
    if (bad < 0) continue;
    std::snprintf(detail_, sizeof detail_,
                  "%s: counts and degrees must rise or fall together from %s through the extra "
                  "points to %s",
                  pot_point_key(axis, bad, cal.count), pot_point_key(axis, 0, cal.count),
                  pot_point_key(axis, cal.count - 1, cal.count));
    return {Error::kOutOfRange, detail_};
  }
  if (get(Id::kAzPwmSlowDuty) > get(Id::kAzPwmFastDuty) ||
      get(Id::kElPwmSlowDuty) > get(Id::kElPwmFastDuty))
    return {Error::kOutOfRange, "the slow PWM duty must not exceed the fast duty"};
  if (const auto pins = check_pins(*this, detail_, sizeof detail_)) return {*pins, detail_};
  if (const auto lines = check_gpiod_lines(*this, detail_, sizeof detail_))
    return {*lines, detail_};
  if (get(Id::kMagXMin) >= get(Id::kMagXMax) || get(Id::kMagYMin) >= get(Id::kMagYMax))
    return {Error::kOutOfRange, "mag.x_min and mag.y_min must be below mag.x_max and mag.y_max"};
  // As with the buttons below, either port's wiring will do.
  const bool pico_i2c = i(Id::kPinI2cSda) != kNoPin && i(Id::kPinI2cScl) != kNoPin;
  if (i(Id::kAzSensor) == 2 && !pico_i2c && i(Id::kI2cBus) < 0)
    return {Error::kOutOfRange,
            "az.sensor = mag needs pins.i2c_sda and pins.i2c_scl (Pico W) or i2c.bus (Raspberry "
            "Pi)"};
  // The table holds both ports' pins; either pair wires the buttons (the
  // core cannot tell whether it runs on a Pico W or under rotord --hw gpiod).
  const bool pico_buttons = i(Id::kPinBtnCw) != kNoPin && i(Id::kPinBtnCcw) != kNoPin;
  const bool pi_buttons = i(Id::kGpiodBtnCw) >= 0 && i(Id::kGpiodBtnCcw) >= 0;
  if (b(Id::kButtonsEnabled) && !pico_buttons && !pi_buttons)
    return {Error::kOutOfRange,
            "buttons.enabled needs pins.btn_cw and pins.btn_ccw (Pico W) or gpiod.btn_cw and "
            "gpiod.btn_ccw (Raspberry Pi)"};
  if (const Rejection net = check_network(); net.error != Error::kOk) return net;
  return {};
}

Rejection Settings::check_network() const {
  if (b(Id::kTimeSntpEnabled) && text(Id::kTimeSntpServer).empty())
    return {Error::kOutOfRange, "time.sntp_enabled needs time.sntp_server"};
  if (i(Id::kNetIpv4Mode) != 1) return {};  // dhcp: the static fields are ignored
  std::uint32_t address = 0;
  std::uint32_t mask = 0;
  if (!parse_ipv4(text(Id::kNetIpv4Address), address))
    return {Error::kOutOfRange, "net.ipv4_mode = static needs net.ipv4_address"};
  if (!parse_ipv4(text(Id::kNetIpv4Netmask), mask))
    return {Error::kOutOfRange, "net.ipv4_mode = static needs net.ipv4_netmask"};
  // A netmask is ones then zeros: ~mask + 1 is then a power of two.
  const std::uint32_t host_bits = ~mask;
  if (mask == 0 || (host_bits & (host_bits + 1)) != 0 || host_bits == 0)
    return {Error::kOutOfRange,
            "net.ipv4_netmask must be ones then zeros, 0.0.0.0 and 255.255.255.255 excluded "
            "(e.g. 255.255.255.0)"};
  if ((address & host_bits) == 0 || (address & host_bits) == host_bits)
    return {Error::kOutOfRange,
            "net.ipv4_address is the network or broadcast address of net.ipv4_netmask"};
  std::uint32_t gateway = 0;
  if (parse_ipv4(text(Id::kNetIpv4Gateway), gateway) &&
      ((gateway & mask) != (address & mask) || gateway == address))
    return {Error::kOutOfRange,
            "net.ipv4_gateway must be another address in the subnet of net.ipv4_address"};
  return {};
}

std::size_t Settings::format_value(Id id, char* out, std::size_t capacity) const {
  if (!is_text(id)) return format(id, get(id), out, capacity);
  if (capacity == 0) return 0;
  const std::string_view t = visible_text(id);
  const std::size_t n = t.size() < capacity ? t.size() : capacity - 1;
  if (n > 0) std::memcpy(out, t.data(), n);
  out[n] = '\0';
  return n;
}

std::size_t Settings::format(Id id, double value, char* out, std::size_t capacity) {
  const Def& d = def(id);
  int n = 0;
  switch (d.type) {
    case Type::kBool:
      n = std::snprintf(out, capacity, "%s", value != 0.0 ? "true" : "false");
      break;
    case Type::kEnum: {
      std::string_view name = choice_name(id, static_cast<int>(value));
      n = std::snprintf(out, capacity, "%.*s", static_cast<int>(name.size()), name.data());
      break;
    }
    case Type::kInt:
      n = std::snprintf(out, capacity, "%ld", static_cast<long>(value));
      break;
    case Type::kFloat:
      // The fewest digits that read back as the same value: 0.15 as typed,
      // yet a computed calibration (62.045454...) survives an export and
      // re-import unchanged. 17 significant digits always round-trip a double.
      for (const int digits : {6, 9, 17}) {
        n = std::snprintf(out, capacity, "%.*g", digits, value);
        if (n < 0 || static_cast<std::size_t>(n) >= capacity) break;
        double back = 0.0;
        if (text::parse_double(std::string_view(out, static_cast<std::size_t>(n)), back) &&
            back == value)
          break;
      }
      break;
    case Type::kText:  // no number to format: format_value prints the text
      n = std::snprintf(out, capacity, "%s", "");
      break;
  }
  if (n < 0) return 0;
  return static_cast<std::size_t>(n) < capacity ? static_cast<std::size_t>(n) : capacity - 1;
}

}  // namespace rotord::settings
