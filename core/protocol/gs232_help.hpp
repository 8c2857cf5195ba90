#pragma once
#include <string_view>

namespace rotord::protocol::gs232 {

/// The H (page 1: azimuth), H2 (page 2: elevation) and, on the GS-232B, H3
/// (page 3: range and centre) command lists, in our own words, each line
/// ending in CR LF like every data reply. Empty for other pages.
std::string_view help_page(int page);

}  // namespace rotord::protocol::gs232
