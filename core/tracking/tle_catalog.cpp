#include "tracking/tle_catalog.hpp"

#include <cstdio>
#include <cstring>

#include "tracking/sky_target.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::tracking {
namespace {

/// Splits `text` into lines (LF or CR LF), one per call.
class Lines {
 public:
  explicit Lines(std::string_view text) : rest_(text) {}
  bool next(std::string_view& line) {
    if (rest_.empty()) return false;
    const std::size_t end = rest_.find('\n');
    line = text::slice(rest_, 0, end);
    rest_ = end == std::string_view::npos ? std::string_view{} : text::slice(rest_, end + 1);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
      line.remove_suffix(1);
    return true;
  }

 private:
  std::string_view rest_;
};

bool starts(std::string_view line, char digit) {
  return line.size() >= 2 && line[0] == digit && line[1] == ' ';
}

void copy_text(std::string_view from, char* to, std::size_t capacity) {
  const std::size_t n = from.size() < capacity - 1 ? from.size() : capacity - 1;
  std::memcpy(to, from.data(), n);
  to[n] = '\0';
}

char upper(char c) {
  return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
}

/// One set found by the strict walk: its title (may be empty) and lines.
struct Set {
  std::string_view title, line1, line2;
};

/// Walks a pasted text strictly: blank lines are skipped, every other line
/// must belong to a set (an optional title, line 1, line 2). Calls `fn` per
/// set; stops at the first stray line (returns its 1-based number) or when
/// `fn` returns false (returns 0).
template <typename Fn>
std::size_t walk(std::string_view text, Fn fn, bool& stopped) {
  Lines lines(text);
  std::string_view line;
  std::size_t number = 0;
  Set set;
  int state = 0;  // 0: expect title or line 1; 1: expect line 1; 2: expect line 2
  std::size_t title_line = 0;
  stopped = false;
  while (lines.next(line)) {
    ++number;
    std::string_view t = text::trim(line);
    if (t.empty()) continue;
    if (state == 2) {
      if (!starts(line, '2')) return number;
      set.line2 = line;
      if (!fn(set)) {
        stopped = true;
        return 0;
      }
      set = {};
      state = 0;
      continue;
    }
    if (starts(line, '1')) {
      set.line1 = line;
      state = 2;
      continue;
    }
    if (state == 1 || starts(line, '2')) return state == 1 ? title_line : number;
    if (t.size() >= 2 && t[0] == '0' && t[1] == ' ') t.remove_prefix(2);
    set.title = text::trim(t);
    title_line = number;
    state = 1;
  }
  if (state == 1) return title_line;
  if (state == 2) return number + 1;
  return 0;
}

}  // namespace

std::size_t TleCheck::describe(char* out, std::size_t capacity) const {
  int n = 0;
  switch (problem) {
    case Problem::kOk:
      n = std::snprintf(out, capacity, "ok");
      break;
    case Problem::kNoSets:
      n = std::snprintf(out, capacity, "no two-line element set found");
      break;
    case Problem::kStray:
      n = std::snprintf(out, capacity,
                        "line %u belongs to no element set (a title, line 1 and line 2 each)",
                        static_cast<unsigned>(set));
      break;
    case Problem::kParse:
      n = std::snprintf(out, capacity, "set %u: %s%s%s", static_cast<unsigned>(set),
                        tle_error_name(tle_error), field[0] != '\0' ? " in " : "", field);
      break;
    case Problem::kSgp4:
      n = std::snprintf(out, capacity, "set %u: SGP4 refuses the elements (%s)",
                        static_cast<unsigned>(set), sgp4_error_name(sgp4));
      break;
    case Problem::kDecayed:
      n = std::snprintf(out, capacity, "set %u: SGP4 cannot propagate it to now (%s)",
                        static_cast<unsigned>(set), sgp4_error_name(sgp4));
      break;
    case Problem::kFull:
      n = std::snprintf(out, capacity, "the store holds at most %u objects",
                        static_cast<unsigned>(TleCatalog::kCapacity));
      break;
  }
  return n < 0 ? 0
               : (static_cast<std::size_t>(n) < capacity ? static_cast<std::size_t>(n)
                                                         : capacity - 1);
}

TleCheck TleCatalog::put(std::string_view text, std::int64_t utc_ms) {
  TleCheck check;
  // First pass: everything must be good; count what is new.
  std::size_t sets = 0;
  std::uint32_t seen[kCapacity * 2] = {};
  std::size_t seen_count = 0;
  bool stopped = false;
  SkyTarget target;  // ~1.2 KB on the stack: PUT /api/tle only, never the tick
  const std::size_t stray = walk(
      text,
      [&](const Set& s) {
        ++sets;
        Tle tle;
        const TleResult r = parse_tle(s.line1, s.line2, tle);
        if (!r.ok()) {
          check = {TleCheck::Problem::kParse, sets, r.error, r.field};
          return false;
        }
        const Sgp4Error e = target.set_satellite(tle);
        if (e != Sgp4Error::kOk) {
          check = {TleCheck::Problem::kSgp4, sets};
          check.sgp4 = e;
          return false;
        }
        if (utc_ms != 0) {
          // Later too: a day after now is where a pass search looks.
          LookAngles look;
          const Observer nowhere;
          for (const std::int64_t t : {utc_ms, utc_ms + std::int64_t{86400000}}) {
            const Sgp4Error p = target.look(t, nowhere, look);
            if (p != Sgp4Error::kOk) {
              check = {TleCheck::Problem::kDecayed, sets};
              check.sgp4 = p;
              return false;
            }
          }
        }
        bool known = find(text::slice(s.line1, 2, 5)) != nullptr;
        for (std::size_t i = 0; i < seen_count && !known; ++i) known = seen[i] == tle.catalog;
        if (!known) {
          if (seen_count < kCapacity * 2) seen[seen_count++] = tle.catalog;
          ++check.added;
        } else {
          ++check.replaced;
        }
        return true;
      },
      stopped);
  if (stopped) return check;
  if (stray != 0) return {TleCheck::Problem::kStray, stray};
  if (sets == 0) return {TleCheck::Problem::kNoSets};
  if (count_ + check.added > kCapacity) {
    TleCheck full{TleCheck::Problem::kFull};
    return full;
  }
  // Second pass: store.
  walk(
      text,
      [&](const Set& s) {
        Tle tle;
        parse_tle(s.line1, s.line2, tle);
        Entry* e = nullptr;
        for (std::size_t i = 0; i < count_ && e == nullptr; ++i)
          if (entries_[i].catalog == tle.catalog) e = &entries_[i];
        if (e == nullptr) e = &entries_[count_++];
        *e = Entry{};
        copy_text(s.title.empty() ? text::slice(s.line1, 2, 5) : s.title, e->name, sizeof e->name);
        copy_text(s.line1, e->line1, sizeof e->line1);
        copy_text(s.line2, e->line2, sizeof e->line2);
        e->catalog = tle.catalog;
        return true;
      },
      stopped);
  return check;
}

TleCatalog::Refresh TleCatalog::refresh(std::string_view text) {
  Refresh r;
  TleSetReader reader(text);
  std::string_view title, line1, line2;
  SkyTarget target;  // ~1.2 KB on the stack: a refresh, never the tick
  while (reader.next(title, line1, line2)) {
    Tle tle;
    if (!parse_tle(line1, line2, tle).ok() || target.set_satellite(tle) != Sgp4Error::kOk) {
      ++r.bad;
      continue;
    }
    Entry* e = nullptr;
    for (std::size_t i = 0; i < count_ && e == nullptr; ++i)
      if (entries_[i].catalog == tle.catalog) e = &entries_[i];
    if (e == nullptr) {
      ++r.not_stored;
      continue;
    }
    // The stored name stays (the user may have named it); the lines change.
    copy_text(line1, e->line1, sizeof e->line1);
    copy_text(line2, e->line2, sizeof e->line2);
    ++r.updated;
  }
  return r;
}

bool TleCatalog::remove(std::uint32_t catalog) {
  for (std::size_t i = 0; i < count_; ++i) {
    if (entries_[i].catalog != catalog) continue;
    for (std::size_t j = i + 1; j < count_; ++j) entries_[j - 1] = entries_[j];
    --count_;
    return true;
  }
  return false;
}

const TleCatalog::Entry* TleCatalog::find(std::string_view key) const {
  key = text::trim(key);
  if (key.empty()) return nullptr;
  std::uint32_t catalog = 0;
  const bool numeric =
      key.size() <= 5 && parse_catalog_number(key.size() == 5 ? key : std::string_view{}, catalog);
  bool digits = !key.empty() && key.size() <= 9;
  std::uint32_t value = 0;
  for (const char c : key) {
    if (c < '0' || c > '9') digits = false;
    if (digits) value = value * 10 + static_cast<std::uint32_t>(c - '0');
  }
  for (std::size_t i = 0; i < count_; ++i) {
    const Entry& e = entries_[i];
    if ((numeric && e.catalog == catalog) || (digits && e.catalog == value)) return &e;
    const std::string_view name(e.name);
    if (name.size() != key.size()) continue;
    bool same = true;
    for (std::size_t k = 0; k < name.size() && same; ++k) same = upper(name[k]) == upper(key[k]);
    if (same) return &e;
  }
  return nullptr;
}

bool TleCatalog::elements(const Entry& entry, Tle& out) {
  Tle tle;
  if (!parse_tle(entry.line1, entry.line2, tle).ok()) return false;
  copy_text(entry.name, tle.name, sizeof tle.name);
  out = tle;
  return true;
}

std::size_t TleCatalog::write_text(char* out, std::size_t capacity) const {
  std::size_t used = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Entry& e = entries_[i];
    const int n =
        std::snprintf(out + used, capacity - used, "%s\n%s\n%s\n", e.name, e.line1, e.line2);
    if (n < 0 || static_cast<std::size_t>(n) >= capacity - used) break;
    used += static_cast<std::size_t>(n);
  }
  return used;
}

void TleCatalog::read_text(std::string_view text) {
  count_ = 0;
  TleSetReader reader(text);
  std::string_view title, line1, line2;
  while (count_ < kCapacity && reader.next(title, line1, line2)) {
    Tle tle;
    if (!parse_tle(line1, line2, tle).ok()) continue;
    Entry& e = entries_[count_++];
    e = Entry{};
    copy_text(title.empty() ? text::slice(line1, 2, 5) : title, e.name, sizeof e.name);
    copy_text(line1, e.line1, sizeof e.line1);
    copy_text(line2, e.line2, sizeof e.line2);
    e.catalog = tle.catalog;
  }
}

bool TleCatalog::save(hal::Storage& storage, char* buf, std::size_t capacity) const {
  return storage.save(std::string_view(buf, write_text(buf, capacity)));
}

void TleCatalog::load(hal::Storage& storage, char* buf, std::size_t capacity) {
  const long n = storage.load(buf, capacity);
  if (n < 0) {
    count_ = 0;
    return;
  }
  read_text(std::string_view(buf, static_cast<std::size_t>(n)));
}

}  // namespace rotord::tracking
