#include "json/json_members.hpp"

#include <cstdio>
#include <cstring>

namespace rotord::web {

bool read_members(std::string_view body, std::span<JsonMember> members, char* why,
                  std::size_t why_bytes) {
  if (body.empty()) return true;
  JsonObjectReader reader(body);
  if (!reader.valid()) {
    std::snprintf(why, why_bytes, "invalid JSON: %s (byte %u)", reader.error(),
                  static_cast<unsigned>(reader.error_offset()));
    return false;
  }
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    JsonMember* found = nullptr;
    for (JsonMember& m : members)
      if (key == m.name) found = &m;
    if (found == nullptr) {
      std::snprintf(why, why_bytes, "unknown member '%.*s'",
                    static_cast<int>(key.size() > 40 ? 40 : key.size()), key.data());
      return false;
    }
    if (value.type != found->type) {
      std::snprintf(why, why_bytes, "%s must be a %s", found->name, json_type_name(found->type));
      return false;
    }
    found->present = true;
    found->value = value;
    if (value.type == JsonType::kString) {
      const std::span<char> to =
          found->text_buffer_.empty() ? std::span<char>(found->short_text_) : found->text_buffer_;
      found->too_long = value.truncated || value.text.size() >= to.size();
      const std::size_t n = found->too_long ? 0 : value.text.size();
      std::memcpy(to.data(), value.text.data(), n);
      to[n] = '\0';
      found->value.text = std::string_view(to.data(), n);
    }
  }
  return true;
}

}  // namespace rotord::web
