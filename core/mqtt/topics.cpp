#include "mqtt/topics.hpp"
#include "util/slice.hpp"

#include <cstring>

namespace rotord::mqtt {

bool valid_prefix(std::string_view prefix) {
  if (prefix.empty() || prefix.size() > kMaxPrefixBytes) return false;
  if (prefix.front() == '/' || prefix.back() == '/') return false;
  char previous = '\0';
  for (char c : prefix) {
    if (c <= 0x20 || c > 0x7e || c == '+' || c == '#') return false;
    if (c == '/' && previous == '/') return false;
    previous = c;
  }
  return true;
}

std::size_t make_prefix(std::string_view setting, std::string_view host_name, char* out,
                        std::size_t cap) {
  std::size_t len = 0;
  if (!setting.empty()) {
    if (setting.size() + 1 > cap) return 0;
    if (!setting.empty()) std::memcpy(out, setting.data(), setting.size());
    len = setting.size();
  } else {
    static constexpr std::string_view kRoot = "rotord/";
    const std::string_view host = host_name.empty() ? std::string_view("rotord") : host_name;
    if (kRoot.size() + host.size() + 1 > cap) return 0;
    if (!kRoot.empty()) std::memcpy(out, kRoot.data(), kRoot.size());
    if (!host.empty()) std::memcpy(out + kRoot.size(), host.data(), host.size());
    len = kRoot.size() + host.size();
  }
  out[len] = '\0';
  return valid_prefix(std::string_view(out, len)) ? len : 0;
}

std::size_t make_node_id(std::string_view from, char* out, std::size_t cap) {
  std::size_t n = 0;
  for (char c : from) {
    if (n + 1 >= cap) break;
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    out[n++] = ok ? c : '_';
  }
  if (cap > 0) out[n] = '\0';
  return n;
}

std::size_t join_topic(std::string_view prefix, std::string_view suffix, char* out,
                       std::size_t cap) {
  const std::size_t len = prefix.size() + 1 + suffix.size();
  if (len + 1 > cap) return 0;
  if (!prefix.empty()) std::memcpy(out, prefix.data(), prefix.size());
  out[prefix.size()] = '/';
  if (!suffix.empty()) std::memcpy(out + prefix.size() + 1, suffix.data(), suffix.size());
  out[len] = '\0';
  return len;
}

std::string_view command_name(std::string_view prefix, std::string_view topic) {
  static constexpr std::string_view kCmd = "/cmd/";
  if (topic.size() <= prefix.size() + kCmd.size()) return {};
  if (text::slice(topic, 0, prefix.size()) != prefix) return {};
  if (text::slice(topic, prefix.size(), kCmd.size()) != kCmd) return {};
  const std::string_view name = text::slice(topic, prefix.size() + kCmd.size());
  if (name.find('/') != std::string_view::npos) return {};
  return name;
}

}  // namespace rotord::mqtt
