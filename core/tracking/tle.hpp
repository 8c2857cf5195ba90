#pragma once
#include <cstdint>
#include <string_view>

namespace rotord::tracking {

/// What is wrong with a two-line element set; kOk when nothing is.
enum class TleError : std::uint8_t {
  kOk = 0,
  kLineLength,       ///< a line is shorter than 69 characters (or longer, unless allowed)
  kLineNumber,       ///< line 1 does not start with "1 ", line 2 with "2 "
  kChecksum,         ///< the modulo-10 checksum in column 69 does not match
  kField,            ///< a field is not a number of its column format (see TleResult::field)
  kCatalogMismatch,  ///< lines 1 and 2 name different catalog numbers
  kNoElements,       ///< no line pair found (TleSetReader)
};

/// A readable name of the error ("checksum", ...), for protocol and CLI messages.
const char* tle_error_name(TleError error);

/// The elements of a TLE as printed (degrees, revolutions per day, the epoch as
/// year and fractional day of year), before SGP4's unit conversions.
struct Tle {
  char name[25] = {};         ///< from a title line (line 0), if any; NUL-terminated
  std::uint32_t catalog = 0;  ///< NORAD number; Alpha-5 ("A0001" = 100001) decoded
  char classification = 'U';  ///< U, C or S
  char designator[9] = {};    ///< international designator, e.g. "98067A"
  int epoch_year = 0;         ///< four digits (two-digit years < 57 are 20xx)
  double epoch_day = 0;       ///< day of year, 1.0 = January 1st 00:00 UTC
  double ndot = 0;            ///< first derivative of mean motion / 2, rev/day^2
  double nddot = 0;           ///< second derivative of mean motion / 6, rev/day^3
  double bstar = 0;           ///< drag term, 1/earth radii
  double inclination_deg = 0;
  double raan_deg = 0;  ///< right ascension of the ascending node
  double eccentricity = 0;
  double arg_perigee_deg = 0;
  double mean_anomaly_deg = 0;
  double mean_motion_rev_day = 0;
  std::uint32_t revolution = 0;  ///< revolution number at epoch
  std::uint32_t element_set = 0;
};

/// The result of parsing: the error and, for kField, the field's name
/// ("eccentricity", ...) so that a message can point at it.
struct TleResult {
  TleError error = TleError::kOk;
  const char* field = "";
  bool ok() const { return error == TleError::kOk; }
};

struct TleParseOptions {
  /// Vallado's verification set holds deliberately invalid cases whose
  /// checksums were not updated; everything else must check them.
  bool verify_checksum = true;
  /// Vallado's verification set appends start/stop/step after column 69.
  bool allow_trailing_text = false;
};

/// Parses lines 1 and 2 (trailing CR/LF/spaces ignored). Fixed columns as in
/// CelesTrak's and Space-Track's documentation; blank fields that SGP4 does not
/// use (designator, element set number, ephemeris type) are accepted, as
/// Vallado's reader does. Leaves `out.name` alone.
TleResult parse_tle(std::string_view line1, std::string_view line2, Tle& out,
                    const TleParseOptions& options = {});

/// The checksum a line should carry in column 69: digits summed, '-' counts 1.
int tle_checksum(std::string_view line);

/// Decodes a catalog number field of five characters: "25544", or Alpha-5
/// ("A0001".."Z9999", letters I and O unused, 100000..339999).
bool parse_catalog_number(std::string_view field, std::uint32_t& out);

/// Walks a text of two- or three-line element sets (CelesTrak's format: an
/// optional title line before each pair; CR/LF or LF line ends). Needs no copy
/// of the text: it keeps views into it, so the text must outlive the reader.
class TleSetReader {
 public:
  explicit TleSetReader(std::string_view text) : rest_(text) {}
  /// The next element set: its title (empty if none) and its two lines, or false
  /// at the end of the text. Lines that fit no set are skipped.
  bool next(std::string_view& title, std::string_view& line1, std::string_view& line2);

 private:
  std::string_view next_line();
  std::string_view rest_;
};

/// Finds the element set titled `name` (case-insensitive, surrounding blanks
/// ignored; an empty name takes the first set) in `text` and parses it.
TleResult find_tle(std::string_view text, std::string_view name, Tle& out,
                   const TleParseOptions& options = {});

}  // namespace rotord::tracking
