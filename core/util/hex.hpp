#pragma once
// Lower-case hex for the access-control records (password hashes, token
// hashes, session ids): plain text that survives JSON, settings files and
// cookies without escaping.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace rotord::hex {

/// Writes 2 * bytes.size() characters to `out` (no NUL).
void encode(std::span<const std::uint8_t> bytes, char* out);

/// Reads exactly 2 * out.size() hex digits (either case); false on any other text.
bool decode(std::string_view text, std::span<std::uint8_t> out);

}  // namespace rotord::hex
