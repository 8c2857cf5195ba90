#pragma once
#include <string_view>

namespace rotord::protocol::rotctld {

/// Reads a number the way rotctld's `sscanf(arg, "%f")` does: the longest
/// decimal prefix counts ("10abc" is 10), a leading '+' or '-' is allowed and,
/// as in rotctld's set_pos, the first ',' is a decimal point ("10,5" is 10.5;
/// Gpredict prints numbers in the user's locale; the locator helpers, which
/// rotctld reads with a plain sscanf, pass false). Unlike sscanf it refuses
/// inf, nan and hex, so no client can send a non-finite target.
bool scan_float(std::string_view token, double& out, bool comma_is_point = true);

/// `sscanf(arg, "%d")`: an optionally signed decimal prefix ("2.5" is 2).
/// Refuses more than 9 digits instead of overflowing.
bool scan_int(std::string_view token, long& out);

}  // namespace rotord::protocol::rotctld
