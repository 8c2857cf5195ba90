#include "tracking/tle.hpp"

#include <cmath>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::tracking {
namespace {

constexpr std::size_t kLineChars = 69;

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::string_view strip_line_end(std::string_view line) {
  while (!line.empty() &&
         (line.back() == '\r' || line.back() == '\n' || line.back() == ' ' || line.back() == '\t'))
    line.remove_suffix(1);
  return line;
}

/// Columns `first`..`last` (1-based, inclusive, as the format is documented).
std::string_view columns(std::string_view line, std::size_t first, std::size_t last) {
  return text::slice(line, first - 1, last - first + 1);
}

/// A decimal field: optional sign, digits with at most one '.', blanks around.
bool decimal_field(std::string_view field, double& out) {
  const std::string_view t = text::trim(field);
  if (t.empty()) return false;
  for (char c : t)
    if (!is_digit(c) && c != '.' && c != '-' && c != '+') return false;
  return text::parse_double(t, out);
}

/// An unsigned integer field; all blanks reads 0 when `blank_is_zero`.
bool unsigned_field(std::string_view field, std::uint32_t& out, bool blank_is_zero) {
  const std::string_view t = text::trim(field);
  if (t.empty()) {
    out = 0;
    return blank_is_zero;
  }
  std::uint32_t value = 0;
  for (char c : t) {
    if (!is_digit(c)) return false;
    value = value * 10 + static_cast<std::uint32_t>(c - '0');
  }
  out = value;
  return true;
}

/// The "implied decimal point, exponent" fields: " 12345-3" = 0.12345e-3.
/// Blanks in the mantissa read as zeros (Vallado's reader does the same).
bool exponent_field(std::string_view field, double& out) {
  // field: sign, five digits, exponent sign, exponent digit (8 characters).
  double sign = 1.0;
  if (field[0] == '-') {
    sign = -1.0;
  } else if (field[0] != ' ' && field[0] != '+') {
    return false;
  }
  double mantissa = 0.0;
  for (std::size_t i = 1; i <= 5; ++i) {
    const char c = field[i];
    if (c != ' ' && !is_digit(c)) return false;
    mantissa = mantissa * 10.0 + (c == ' ' ? 0 : c - '0');
  }
  int exponent_sign = 1;
  if (field[6] == '-') {
    exponent_sign = -1;
  } else if (field[6] != '+' && field[6] != ' ') {
    return false;
  }
  const char e = field[7] == ' ' ? '0' : field[7];
  if (!is_digit(e)) return false;
  out = sign * mantissa / 100000.0 * std::pow(10.0, exponent_sign * (e - '0'));
  return true;
}

TleResult field_error(const char* name) {
  return {TleError::kField, name};
}

TleResult check_line(std::string_view line, char number, const TleParseOptions& options) {
  if (line.size() < kLineChars || (line.size() > kLineChars && !options.allow_trailing_text))
    return {TleError::kLineLength, number == '1' ? "line 1" : "line 2"};
  if (line[0] != number || line[1] != ' ')
    return {TleError::kLineNumber, number == '1' ? "line 1" : "line 2"};
  if (options.verify_checksum && (!is_digit(line[68]) || tle_checksum(line) != line[68] - '0'))
    return {TleError::kChecksum, number == '1' ? "line 1" : "line 2"};
  return {};
}

void copy_trimmed(std::string_view from, char* to, std::size_t capacity) {
  from = text::trim(from);
  std::size_t n = 0;
  for (; n < from.size() && n + 1 < capacity; ++n) to[n] = from[n];
  to[n] = '\0';
}

char upper(char c) {
  return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
}

}  // namespace

const char* tle_error_name(TleError error) {
  switch (error) {
    case TleError::kOk:
      return "ok";
    case TleError::kLineLength:
      return "line length";
    case TleError::kLineNumber:
      return "line number";
    case TleError::kChecksum:
      return "checksum";
    case TleError::kField:
      return "bad field";
    case TleError::kCatalogMismatch:
      return "catalog numbers differ";
    case TleError::kNoElements:
      return "no element set";
  }
  return "?";
}

int tle_checksum(std::string_view line) {
  int sum = 0;
  for (std::size_t i = 0; i < line.size() && i < kLineChars - 1; ++i) {
    if (is_digit(line[i])) sum += line[i] - '0';
    if (line[i] == '-') sum += 1;
  }
  return sum % 10;
}

bool parse_catalog_number(std::string_view field, std::uint32_t& out) {
  if (field.size() != 5) return false;
  std::uint32_t rest = 0;
  if (!unsigned_field(text::slice(field, 1), rest, false) ||
      text::trim(text::slice(field, 1)).size() != 4) {
    // Old TLEs pad small numbers with blanks ("    5"): accept them, digits only.
    return unsigned_field(field, out, false);
  }
  const char first = upper(field[0]);
  if (first == ' ' || is_digit(first)) {
    const std::uint32_t head = first == ' ' ? 0u : static_cast<std::uint32_t>(first - '0');
    out = head * 10000 + rest;
    return true;
  }
  // Alpha-5: A=10 .. Z=33, skipping I and O (they read as 1 and 0).
  if (first < 'A' || first > 'Z' || first == 'I' || first == 'O') return false;
  std::uint32_t value = static_cast<std::uint32_t>(first - 'A') + 10;
  if (first > 'I') --value;
  if (first > 'O') --value;
  out = value * 10000 + rest;
  return true;
}

TleResult parse_tle(std::string_view line1, std::string_view line2, Tle& out,
                    const TleParseOptions& options) {
  line1 = strip_line_end(line1);
  line2 = strip_line_end(line2);
  if (TleResult r = check_line(line1, '1', options); !r.ok()) return r;
  if (TleResult r = check_line(line2, '2', options); !r.ok()) return r;

  Tle t;
  for (std::size_t i = 0; i < sizeof t.name; ++i) t.name[i] = out.name[i];
  if (!parse_catalog_number(columns(line1, 3, 7), t.catalog)) return field_error("catalog number");
  std::uint32_t catalog2 = 0;
  if (!parse_catalog_number(columns(line2, 3, 7), catalog2)) return field_error("catalog number");
  if (catalog2 != t.catalog) return {TleError::kCatalogMismatch, "catalog number"};
  t.classification = line1[7] == ' ' ? 'U' : line1[7];
  copy_trimmed(columns(line1, 10, 17), t.designator, sizeof t.designator);

  std::uint32_t year2 = 0;
  if (!unsigned_field(columns(line1, 19, 20), year2, false) || year2 > 99)
    return field_error("epoch year");
  t.epoch_year = static_cast<int>(year2 < 57 ? 2000 + year2 : 1900 + year2);
  if (!decimal_field(columns(line1, 21, 32), t.epoch_day) || t.epoch_day < 1.0 ||
      t.epoch_day >= 367.0)
    return field_error("epoch day");
  if (!decimal_field(columns(line1, 34, 43), t.ndot)) return field_error("ndot");
  if (!exponent_field(columns(line1, 45, 52), t.nddot)) return field_error("nddot");
  if (!exponent_field(columns(line1, 54, 61), t.bstar)) return field_error("bstar");
  if (!unsigned_field(columns(line1, 65, 68), t.element_set, true))
    return field_error("element set number");

  if (!decimal_field(columns(line2, 9, 16), t.inclination_deg) || t.inclination_deg < 0.0 ||
      t.inclination_deg > 180.0)
    return field_error("inclination");
  if (!decimal_field(columns(line2, 18, 25), t.raan_deg) || t.raan_deg < 0.0 || t.raan_deg > 360.0)
    return field_error("right ascension");
  std::uint32_t ecc_digits = 0;
  const std::string_view ecc = columns(line2, 27, 33);
  {
    // Seven digits with an implied leading decimal point; blanks read as zeros.
    for (char c : ecc) {
      if (c == ' ') c = '0';
      if (!is_digit(c)) return field_error("eccentricity");
      ecc_digits = ecc_digits * 10 + static_cast<std::uint32_t>(c - '0');
    }
    t.eccentricity = static_cast<double>(ecc_digits) / 1e7;
  }
  if (!decimal_field(columns(line2, 35, 42), t.arg_perigee_deg) || t.arg_perigee_deg < 0.0 ||
      t.arg_perigee_deg > 360.0)
    return field_error("argument of perigee");
  if (!decimal_field(columns(line2, 44, 51), t.mean_anomaly_deg) || t.mean_anomaly_deg < 0.0 ||
      t.mean_anomaly_deg > 360.0)
    return field_error("mean anomaly");
  if (!decimal_field(columns(line2, 53, 63), t.mean_motion_rev_day) || t.mean_motion_rev_day <= 0.0)
    return field_error("mean motion");
  if (!unsigned_field(columns(line2, 64, 68), t.revolution, true))
    return field_error("revolution number");
  out = t;
  return {};
}

std::string_view TleSetReader::next_line() {
  if (rest_.empty()) return {};
  std::size_t end = 0;
  while (end < rest_.size() && rest_[end] != '\n') ++end;
  std::string_view line = text::slice(rest_, 0, end);
  rest_.remove_prefix(end < rest_.size() ? end + 1 : end);
  return strip_line_end(line);
}

bool TleSetReader::next(std::string_view& title, std::string_view& line1, std::string_view& line2) {
  std::string_view previous;
  while (!rest_.empty()) {
    const std::string_view line = next_line();
    if (line.size() >= 2 && line[0] == '1' && line[1] == ' ') {
      // A line 1 must be followed by its line 2; otherwise look on from there.
      const std::string_view saved = rest_;
      const std::string_view candidate = next_line();
      if (candidate.size() >= 2 && candidate[0] == '2' && candidate[1] == ' ') {
        title = previous;
        if (title.size() >= 2 && title[0] == '0' && title[1] == ' ') title.remove_prefix(2);
        title = text::trim(title);
        line1 = line;
        line2 = candidate;
        return true;
      }
      rest_ = saved;
      previous = {};
      continue;
    }
    previous = line;
  }
  return false;
}

TleResult find_tle(std::string_view text_in, std::string_view name, Tle& out,
                   const TleParseOptions& options) {
  name = text::trim(name);
  TleSetReader reader(text_in);
  std::string_view title, line1, line2;
  while (reader.next(title, line1, line2)) {
    if (!name.empty()) {
      if (title.size() != name.size()) continue;
      bool same = true;
      for (std::size_t i = 0; i < name.size() && same; ++i)
        same = upper(title[i]) == upper(name[i]);
      if (!same) continue;
    }
    Tle parsed;
    copy_trimmed(title, parsed.name, sizeof parsed.name);
    const TleResult r = parse_tle(line1, line2, parsed, options);
    if (r.ok()) out = parsed;
    return r;
  }
  return {TleError::kNoElements, name.empty() ? "" : "name"};
}

}  // namespace rotord::tracking
