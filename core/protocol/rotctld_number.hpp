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

/// A whole token that is an optionally signed decimal integer: "1e9", "60.5",
/// "3abc" and "1e400" are refused, where sscanf("%d") would read 1, 60, 3
/// and 1. For the arguments no Hamlib client sends in another form (pause
/// seconds, move direction and speed, speed level, reset), so a typo or a
/// hostile value fails with RPRT -1 instead of acting on a prefix.
bool scan_whole_int(std::string_view token, long& out);

}  // namespace rotord::protocol::rotctld
