#pragma once
#include <cstddef>
#include <string_view>

namespace rotord::text {

/// Removes spaces, tabs, CR and LF at both ends.
std::string_view trim(std::string_view s);

/// Parses a decimal number the way rotator clients write them: optional
/// leading '+' or '-', '.' or ',' as decimal separator (Gpredict uses the
/// user's locale), optional exponent. Rejects empty text, trailing garbage,
/// hex, inf and nan. Written by hand because it must behave the same on the
/// Pico (no locale, no exceptions) as on Linux.
bool parse_double(std::string_view s, double& out);

/// Parses an optionally signed decimal integer; rejects anything else.
bool parse_int(std::string_view s, long& out);

/// Case-insensitive equality for ASCII command words.
bool iequals(std::string_view a, std::string_view b);

/// Splits off the first whitespace-delimited token; `rest` gets the remainder.
std::string_view next_token(std::string_view& rest);

}  // namespace rotord::text
