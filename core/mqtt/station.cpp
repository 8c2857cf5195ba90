#include "mqtt/station.hpp"

#include <cstdlib>
#include <cstring>

#include "util/slice.hpp"

namespace rotord::mqtt {
namespace {

void copy(std::string_view from, char* out, std::size_t cap) {
  const std::size_t n = from.size() < cap - 1 ? from.size() : cap - 1;
  if (n > 0) std::memcpy(out, from.data(), n);  // an empty view's data() may be null
  out[n] = '\0';
}

/// The number after `key` in `json` (rotord's own status JSON, so a plain
/// search is enough); false when absent or not a number.
bool number_after(std::string_view json, std::string_view key, float& out) {
  const std::size_t at = json.find(key);
  if (at == std::string_view::npos) return false;
  const std::size_t start = at + key.size();
  char buf[24];
  std::size_t n = 0;
  while (start + n < json.size() && n + 1 < sizeof buf) {
    const char c = json[start + n];
    if (!((c >= '0' && c <= '9') || c == '-' || c == '.' || c == 'e' || c == 'E' || c == '+'))
      break;
    buf[n] = c;
    ++n;
  }
  if (n == 0) return false;
  buf[n] = '\0';
  char* end = nullptr;
  out = std::strtof(buf, &end);
  return end != buf;
}

/// The string after `key` ("key":"value"), copied; false when absent.
bool string_after(std::string_view json, std::string_view key, char* out, std::size_t cap) {
  const std::size_t at = json.find(key);
  if (at == std::string_view::npos) return false;
  const std::size_t start = at + key.size();
  const std::size_t end = json.find('"', start);
  if (end == std::string_view::npos) return false;
  const std::string_view value = text::slice(json, start, end - start);
  if (value.find('\\') != std::string_view::npos) return false;
  copy(value, out, cap);
  return true;
}

}  // namespace

Station::Entry* Station::find(std::string_view prefix, bool add) {
  for (Entry& e : entries_)
    if (e.used && prefix == e.prefix) return &e;
  if (!add) return nullptr;
  for (Entry& e : entries_) {
    if (e.used) continue;
    e = Entry{};
    e.used = true;
    copy(prefix, e.prefix, sizeof e.prefix);
    return &e;
  }
  return nullptr;
}

bool Station::on_message(std::string_view topic, std::string_view payload) {
  // <a>/<b>/<leaf>
  const std::size_t first = topic.find('/');
  if (first == std::string_view::npos) return false;
  const std::size_t second = topic.find('/', first + 1);
  if (second == std::string_view::npos || topic.find('/', second + 1) != std::string_view::npos)
    return false;
  const std::string_view prefix = text::slice(topic, 0, second);
  const std::string_view leaf = text::slice(topic, second + 1);
  if (prefix.size() > kMaxPrefixBytes) return false;
  if (leaf == "state") {
    // Only rotord's status document counts (other devices use .../state too).
    float az = 0.0f;
    if (payload.find(R"("version":)") == std::string_view::npos ||
        !number_after(payload, R"("az":{"position_deg":)", az))
      return false;
    Entry* e = find(prefix, true);
    if (e == nullptr) return false;
    e->seen_state = true;
    // Where the beam points (issue 26), the mechanism beside it; an older
    // rotord's state has no beam: its mechanism's position is shown then.
    e->mech_az_deg = az;
    if (!number_after(payload, R"("beam":{"az_deg":)", e->az_deg)) e->az_deg = az;
    e->has_el = number_after(payload, R"("el":{"position_deg":)", e->el_deg);
    float beam_el = 0.0f;
    if (e->has_el && number_after(payload, R"(,"el_deg":)", beam_el)) e->el_deg = beam_el;
    if (!string_after(payload, R"("mode":")", e->mode, sizeof e->mode)) e->mode[0] = '\0';
    e->fault = payload.find(R"("fault":true)") != std::string_view::npos;
    return true;
  }
  Entry* e = find(prefix, false);
  if (leaf == "availability") {
    // It may come before the state (retained messages arrive per topic).
    if (payload != "online" && payload != "offline") return false;
    if (e == nullptr) e = find(prefix, true);
    if (e == nullptr) return false;
    e->online = payload == "online";
    return true;
  }
  if (leaf == "info") {
    if (payload.find(R"("rotord":)") == std::string_view::npos) return false;
    if (e == nullptr) e = find(prefix, true);
    if (e == nullptr) return false;
    string_after(payload, R"("name":")", e->name, sizeof e->name);
    // Anyone may publish there: only a plain http(s) address becomes a link.
    char web[kMaxUrlBytes];
    if (string_after(payload, R"("web":")", web, sizeof web)) {
      const std::string_view url(web);
      const bool http = text::slice(url, 0, 7) == "http://" || text::slice(url, 0, 8) == "https://";
      copy(http ? url : std::string_view(), e->web, sizeof e->web);
    }
    return true;
  }
  return false;
}

std::size_t Station::size() const {
  std::size_t n = 0;
  for (const Entry& e : entries_) n += e.used && e.seen_state ? 1 : 0;
  return n;
}

void Station::write_station(web::JsonWriter& w) const {
  w.begin_object().member("available", true).key("rotators").begin_array();
  for (const Entry& e : entries_) {
    if (!e.used || !e.seen_state) continue;
    w.begin_object()
        .member("prefix", e.prefix)
        .member("name", e.name)
        .member("web", e.web)
        .member("online", e.online)
        .member("mode", e.mode)
        .member("az_deg", e.az_deg)
        .member("mech_az_deg", e.mech_az_deg);
    w.key("el_deg");
    if (e.has_el) {
      w.number(e.el_deg);
    } else {
      w.null();
    }
    w.member("fault", e.fault).end_object();
  }
  w.end_array().end_object();
}

}  // namespace rotord::mqtt
