#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "settings/settings.hpp"
#include "util/axis_id.hpp"

namespace rotord::settings {

/// A per-axis row both axes have (axis_settings.def, AXIS_SETTING), for
/// either axis: axis_id(AxisId::kEl, AxisRow::kMinDeg) is Id::kElMinDeg.
/// The rows only the azimuth has (AZ_SETTING) are not among them.
enum class AxisRow : std::uint8_t {
#define AXIS_SETTING(name, ...) k##name,
#define AZ_SETTING(...)
#include "settings/axis_settings.def"
#undef AZ_SETTING
#undef AXIS_SETTING
};

/// How many AxisRows there are.
inline constexpr std::size_t kAxisRowCount = 0
#define AXIS_SETTING(...) +1
#define AZ_SETTING(...)
#include "settings/axis_settings.def"
#undef AZ_SETTING
#undef AXIS_SETTING
    ;

namespace detail {
// Compile time only: every row's Id on each axis, in the file's order.
inline constexpr Id kAzRows[] = {
#define AXIS_SETTING(name, ...) Id::kAz##name,
#define AZ_SETTING(...)
#include "settings/axis_settings.def"
#undef AZ_SETTING
#undef AXIS_SETTING
};
inline constexpr Id kElRows[] = {
#define AXIS_SETTING(name, ...) Id::kEl##name,
#define AZ_SETTING(...)
#include "settings/axis_settings.def"
#undef AZ_SETTING
#undef AXIS_SETTING
};

// The elevation's rows follow one another in the table; the azimuth's have
// its own rows (brake, endless turning) between them, so what the firmware
// keeps is a byte per row: its distance from the first.
inline constexpr Id kAzFirstRow = kAzRows[0];
inline constexpr Id kElFirstRow = kElRows[0];
inline constexpr auto kAzRowOffset = [] {
  std::array<std::uint8_t, kAxisRowCount> offset{};
  for (std::size_t n = 0; n < kAxisRowCount; ++n)
    offset[n] =
        static_cast<std::uint8_t>(static_cast<int>(kAzRows[n]) - static_cast<int>(kAzFirstRow));
  return offset;
}();

constexpr bool rows_are_where_axis_id_finds_them() {
  for (std::size_t n = 0; n < kAxisRowCount; ++n) {
    const int az = static_cast<int>(kAzRows[n]) - static_cast<int>(kAzFirstRow);
    if (az < 0 || az > 255 || az != kAzRowOffset[n]) return false;
    if (static_cast<int>(kElRows[n]) != static_cast<int>(kElFirstRow) + static_cast<int>(n))
      return false;
  }
  return true;
}
static_assert(rows_are_where_axis_id_finds_them());
}  // namespace detail

/// The Id of `row` on `axis`: the one mapping from a per-axis row to its key.
constexpr Id axis_id(AxisId axis, AxisRow row) {
  const auto n = static_cast<std::size_t>(row);
  return axis == AxisId::kAz
             ? static_cast<Id>(static_cast<int>(detail::kAzFirstRow) + detail::kAzRowOffset[n])
             : static_cast<Id>(static_cast<int>(detail::kElFirstRow) + static_cast<int>(n));
}

}  // namespace rotord::settings
