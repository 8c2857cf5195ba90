#include "protocol/flat_xml.hpp"

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

void skip_space(std::string_view& s) {
  std::size_t i = 0;
  while (i < s.size() && is_space(s[i])) ++i;
  s.remove_prefix(i);
}

/// Letters, digits and `_ - . ?`: what the two formats' names hold (`AZ?`
/// appears as a tag in some write-ups of PstRotator's manual).
bool is_name_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.' || c == '?';
}

/// Takes `<name>` (or `</name>` when `closing`) off the front of `s`;
/// returns the name, empty when `s` does not start with one.
std::string_view take_tag(std::string_view& s, bool closing) {
  const std::size_t open = closing ? 2 : 1;
  if (s.size() < open + 2 || s[0] != '<' || (closing && s[1] != '/')) return {};
  std::size_t i = open;
  while (i < s.size() && is_name_char(s[i])) ++i;
  if (i == open || i >= s.size() || s[i] != '>') return {};
  const std::string_view name = text::slice(s, open, i - open);
  s.remove_prefix(i + 1);
  return name;
}

}  // namespace

bool FlatXml::parse(std::string_view message, std::string_view root, std::string_view nestable) {
  count_ = 0;
  std::string_view s = message;
  skip_space(s);
  // An XML declaration, as a library-written message starts.
  if (s.size() >= 2 && s[0] == '<' && s[1] == '?') {
    const std::size_t end = s.find("?>");
    if (end == std::string_view::npos) return false;
    s.remove_prefix(end + 2);
    skip_space(s);
  }
  if (!text::iequals(take_tag(s, false), root)) return false;
  if (!parse_items(s, root, nestable)) return false;
  skip_space(s);
  return s.empty();  // nothing after the root
}

bool FlatXml::parse_content(std::string_view content) {
  count_ = 0;
  return parse_items(content, {}, {});
}

bool FlatXml::parse_items(std::string_view& s, std::string_view root, std::string_view nestable) {
  while (true) {
    skip_space(s);
    if (s.empty()) return root.empty();  // content ends here; a root must close
    if (s[0] != '<') {
      // Bare text up to the next tag (or the end of nested content).
      std::size_t lt = s.find('<');
      if (lt == std::string_view::npos) {
        if (!root.empty()) return false;
        lt = s.size();
      }
      if (count_ == kMaxItems) return false;
      items_[count_++] = {{}, text::trim(text::slice(s, 0, lt)), false};
      s.remove_prefix(lt);
      continue;
    }
    if (s.size() > 1 && s[1] == '/') return !root.empty() && text::iequals(take_tag(s, true), root);
    const std::string_view name = take_tag(s, false);
    if (name.empty()) return false;
    std::string_view rest = s;
    skip_space(rest);
    if (!nestable.empty() && text::iequals(name, nestable) && rest.size() > 1 && rest[0] == '<' &&
        rest[1] != '/') {
      // One level of flat elements inside; checked now, read by the caller.
      FlatXml inner;
      std::string_view content = s;
      if (!inner.parse_items(content, name, {})) return false;
      if (count_ == kMaxItems) return false;
      const std::size_t used = s.size() - content.size();  // content now follows </name>
      const std::size_t close = text::slice(s, 0, used).rfind("</");
      items_[count_++] = {name, text::trim(text::slice(s, 0, close)), true};
      s = content;
      continue;
    }
    // The value runs to the next '<', which must close this element: no
    // nesting, no comments, no CDATA.
    const std::size_t lt = s.find('<');
    if (lt == std::string_view::npos) return false;
    const std::string_view value = text::trim(text::slice(s, 0, lt));
    s.remove_prefix(lt);
    if (!text::iequals(take_tag(s, true), name)) return false;
    if (count_ == kMaxItems) return false;
    items_[count_++] = {name, value, false};
  }
}

std::size_t xml_unescape(std::string_view escaped, char* out, std::size_t capacity) {
  static constexpr struct {
    std::string_view entity;
    char c;
  } kEntities[] = {{"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
  std::size_t n = 0;
  for (std::size_t i = 0; i < escaped.size();) {
    char c = escaped[i];
    std::size_t used = 1;
    if (c == '&') {
      used = 0;
      for (const auto& e : kEntities) {
        if (text::slice(escaped, i, e.entity.size()) == e.entity) {
          c = e.c;
          used = e.entity.size();
          break;
        }
      }
      if (used == 0) return std::string_view::npos;
    }
    if (n == capacity) return std::string_view::npos;
    out[n++] = c;
    i += used;
  }
  return n;
}

}  // namespace rotord::protocol
