#pragma once
#include <cstddef>
#include <string_view>

namespace rotord::mqtt {

/// The longest topic rotord builds or accepts (prefix 63 + "/cmd/" + name).
inline constexpr std::size_t kMaxTopicBytes = 128;
/// The longest prefix (the mqtt.prefix setting's maximum).
inline constexpr std::size_t kMaxPrefixBytes = 63;

/// Whether `prefix` can be a topic prefix: 1..63 printable ASCII, no
/// wildcards ('+', '#'), no spaces, no '/' at either end, no empty level.
bool valid_prefix(std::string_view prefix);

/// The prefix in use: `setting` when not empty, else rotord/<host_name>.
/// Writes it NUL-terminated into `out`; 0 when it is not a valid prefix.
std::size_t make_prefix(std::string_view setting, std::string_view host_name, char* out,
                        std::size_t cap);

/// An id of letters, digits, '_' and '-' only (Home Assistant's node_id and
/// object ids): other characters become '_'. NUL-terminated; returns length.
std::size_t make_node_id(std::string_view from, char* out, std::size_t cap);

/// <prefix>/<suffix>, NUL-terminated; 0 when it does not fit.
std::size_t join_topic(std::string_view prefix, std::string_view suffix, char* out,
                       std::size_t cap);

/// The command name of <prefix>/cmd/<name>, or empty when `topic` is not one.
std::string_view command_name(std::string_view prefix, std::string_view topic);

}  // namespace rotord::mqtt
