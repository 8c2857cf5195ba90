#include "access/web_sessions.hpp"

#include "util/hex.hpp"
#include "util/slice.hpp"

namespace rotord::access {
namespace {

std::string_view trim_spaces(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view cookie_value(std::string_view cookie_header, std::string_view name) {
  while (!cookie_header.empty()) {
    const std::size_t semi = cookie_header.find(';');
    const std::string_view pair = trim_spaces(text::slice(cookie_header, 0, semi));
    const std::size_t eq = pair.find('=');
    if (eq != std::string_view::npos && trim_spaces(text::slice(pair, 0, eq)) == name) {
      std::string_view value = trim_spaces(text::slice(pair, eq + 1));
      // RFC 6265 allows a quoted value.
      if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
        value = text::slice(value, 1, value.size() - 2);
      return value;
    }
    if (semi == std::string_view::npos) break;
    cookie_header.remove_prefix(semi + 1);
  }
  return {};
}

int WebSessions::create(Crypto& crypto, Millis now, Millis lifetime_ms, bool authenticated) {
  std::size_t slot = 0;
  for (std::size_t n = 0; n < entries_.size(); ++n) {
    if (!entries_[n].used) {
      slot = n;
      break;
    }
    if (entries_[n].created < entries_[slot].created) slot = n;
  }
  Entry fresh;
  if (!crypto.random(fresh.id)) return -1;
  fresh.used = true;
  fresh.authenticated = authenticated;
  fresh.created = now;
  fresh.expires = now + lifetime_ms;
  entries_[slot] = fresh;
  return static_cast<int>(slot);
}

int WebSessions::find(Crypto& crypto, std::string_view cookie_header, Millis now) const {
  const std::string_view text = cookie_value(cookie_header, kCookieName);
  Id id{};
  if (!hex::decode(text, id)) return -1;
  int found = -1;
  // Every entry is compared, each in constant time: the answer's timing
  // tells nothing about how close a guess came.
  for (std::size_t n = 0; n < entries_.size(); ++n) {
    const Entry& e = entries_[n];
    const bool match = crypto.equal(e.id, id);
    if (match && e.used && now < e.expires) found = static_cast<int>(n);
  }
  return found;
}

void WebSessions::remove(int index) {
  if (index >= 0 && static_cast<std::size_t>(index) < entries_.size())
    entries_[static_cast<std::size_t>(index)] = Entry{};
}

void WebSessions::remove_all() {
  entries_.fill(Entry{});
}

void WebSessions::expire(Millis now) {
  for (Entry& e : entries_)
    if (e.used && now >= e.expires) e = Entry{};
}

void WebSessions::id_text(int index, char (&out)[kIdTextBytes + 1]) const {
  hex::encode(at(index).id, out);
  out[kIdTextBytes] = '\0';
}

}  // namespace rotord::access
