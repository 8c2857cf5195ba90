#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hal/storage.hpp"
#include "tracking/sgp4.hpp"
#include "tracking/tle.hpp"

namespace rotord::tracking {

/// What is wrong with a pasted TLE text, for PUT /api/tle and the Track page.
struct TleCheck {
  enum class Problem : std::uint8_t {
    kOk,
    kNoSets,   ///< no element set in the text
    kStray,    ///< a line that belongs to no set (a title without lines, a lone line 1 or 2)
    kParse,    ///< the lines do not parse (tle_error/field say why)
    kSgp4,     ///< SGP4 refuses the elements at epoch (sgp4 says why)
    kDecayed,  ///< SGP4 cannot propagate it to now (decayed, or elements gone bad)
    kFull,     ///< more objects than the store holds
  };
  Problem problem = Problem::kOk;
  std::size_t set = 0;  ///< which set (1-based) or line (kStray) is wrong
  TleError tle_error = TleError::kOk;
  const char* field = "";
  Sgp4Error sgp4 = Sgp4Error::kOk;
  std::size_t added = 0;     ///< sets new to the store
  std::size_t replaced = 0;  ///< sets that replaced one of the same catalog number
  bool ok() const { return problem == Problem::kOk; }
  /// One sentence: "set 2: checksum", "line 5 belongs to no element set", ...
  std::size_t describe(char* out, std::size_t capacity) const;
};

/// The stored element sets (Linux: tles.txt beside the settings file; Pico W:
/// flash): at most kCapacity objects, kept as their three lines, saved as a
/// CelesTrak-style three-line text through a hal::Storage. Fixed size, no heap.
class TleCatalog {
 public:
  static constexpr std::size_t kCapacity = 24;
  static constexpr std::size_t kNameBytes = 25;  ///< 24 characters and the NUL
  static constexpr std::size_t kLineBytes = 70;  ///< 69 characters and the NUL
  /// The saved text at most: every object's three lines with CR LF.
  static constexpr std::size_t kMaxTextBytes = kCapacity * (kNameBytes + 2 * kLineBytes + 6);

  struct Entry {
    char name[kNameBytes] = {};
    char line1[kLineBytes] = {};
    char line2[kLineBytes] = {};
    std::uint32_t catalog = 0;
  };

  /// Checks every set of `text` (format, checksums, SGP4 at epoch and, when
  /// `utc_ms` is known (not 0), at `utc_ms`: a decayed object is refused) and
  /// only when all are good stores them: a set replaces the stored one of
  /// the same catalog number. Nothing changes on any error.
  TleCheck put(std::string_view text, std::int64_t utc_ms);
  /// A refresh (a downloaded catalog, e.g. CelesTrak's): every good set
  /// whose catalog number is stored replaces it; the rest is left out. Bad
  /// sets (format, checksum, SGP4 at epoch) are counted and skipped.
  struct Refresh {
    std::size_t updated = 0;
    std::size_t not_stored = 0;
    std::size_t bad = 0;
  };
  Refresh refresh(std::string_view text);
  /// Removes an object; false when it is not stored.
  bool remove(std::uint32_t catalog);
  void clear() { count_ = 0; }

  /// By catalog number ("25544") or title (case-insensitive, "ISS (ZARYA)").
  const Entry* find(std::string_view name_or_catalog) const;
  /// The parsed elements of an entry (stored entries always parse).
  static bool elements(const Entry& entry, Tle& out);

  std::size_t size() const { return count_; }
  const Entry& entry(std::size_t n) const { return entries_[n]; }

  /// The catalog as text (title, line 1, line 2 per object, LF); the length.
  std::size_t write_text(char* out, std::size_t capacity) const;
  /// Loads a saved text, keeping the sets that parse (the store wrote them).
  void read_text(std::string_view text);
  /// Through a port's storage (a file, flash slots). `buf` holds kMaxTextBytes.
  bool save(hal::Storage& storage, char* buf, std::size_t capacity) const;
  void load(hal::Storage& storage, char* buf, std::size_t capacity);

 private:
  Entry entries_[kCapacity];
  std::size_t count_ = 0;
};

}  // namespace rotord::tracking
