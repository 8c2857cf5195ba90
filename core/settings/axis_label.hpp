#pragma once
// The elevation's label of a per-axis row (axis_settings.def), derived from
// the azimuth's at compile time: "Elevation: " and the label with its first
// letter lowered and "azimuth" read "elevation" ("Pot point 1: azimuth" ->
// "Elevation: pot point 1: elevation"), but an acronym kept as it is ("MA3
// encoder zero" -> "Elevation: MA3 encoder zero"); a label that names the elevation
// already is kept as it is (the row gave it with AZ_EL). Each derived label
// is a constant array of its exact length in the firmware's rodata, as a
// written-out literal was: no heap, nothing done at run time.
#include <array>
#include <cstddef>
#include <string_view>

namespace rotord::settings::detail {

/// A string literal as a template argument (C++20 class-type parameter).
template <std::size_t N>
struct LabelLiteral {
  char text[N];
  constexpr LabelLiteral(const char (&literal)[N]) {  // NOLINT: implicit by design
    for (std::size_t n = 0; n < N; ++n) text[n] = literal[n];
  }
  constexpr std::string_view view() const { return {text, N - 1}; }
};

inline constexpr std::string_view kElevationPrefix = "Elevation: ";
inline constexpr std::string_view kAzimuthWord = "azimuth";
inline constexpr std::string_view kElevationWord = "elevation";

/// Whether `word` stands in `label`. By hand, not string_view::find: GCC 12
/// cannot evaluate find's char_traits at compile time on a template
/// parameter object under -fsanitize=undefined (the ASan tree), whose null
/// checks on the pointer it passes are not constant expressions.
constexpr bool contains(std::string_view label, std::string_view word) {
  for (std::size_t n = 0; n + word.size() <= label.size(); ++n) {
    std::size_t same = 0;
    while (same < word.size() && label[n + same] == word[same]) ++same;
    if (same == word.size()) return true;
  }
  return false;
}

constexpr bool names_elevation(std::string_view label) {
  return contains(label, kElevationWord) || contains(label, "Elevation");
}

/// Writes the elevation's label of `label` through `put`, one char at a time
/// (once to count, once to fill).
template <typename Put>
constexpr void derive_elevation_label(std::string_view label, Put put) {
  if (names_elevation(label)) {
    for (char c : label) put(c);
    return;
  }
  for (char c : kElevationPrefix) put(c);
  // The label with its first letter lowered, read through `at`; not when the
  // first word is an acronym (PWM, MA3, ADC): a second capital or a digit.
  const bool acronym = label.size() > 1 && ((label[1] >= 'A' && label[1] <= 'Z') ||
                                            (label[1] >= '0' && label[1] <= '9'));
  const auto at = [label, acronym](std::size_t n) {
    const char c = label[n];
    return n == 0 && !acronym && c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
  };
  for (std::size_t n = 0; n < label.size();) {
    std::size_t same = 0;
    while (same < kAzimuthWord.size() && n + same < label.size() &&
           at(n + same) == kAzimuthWord[same])
      ++same;
    if (same == kAzimuthWord.size()) {
      for (char c : kElevationWord) put(c);
      n += same;
    } else {
      put(at(n++));
    }
  }
}

constexpr std::size_t elevation_label_length(std::string_view label) {
  std::size_t length = 0;
  derive_elevation_label(label, [&length](char) { ++length; });
  return length;
}

template <LabelLiteral kAzimuthLabel>
constexpr auto make_elevation_label() {
  std::array<char, elevation_label_length(kAzimuthLabel.view()) + 1> out{};
  std::size_t at = 0;
  derive_elevation_label(kAzimuthLabel.view(), [&out, &at](char c) { out[at++] = c; });
  out[at] = '\0';
  return out;
}

template <LabelLiteral kAzimuthLabel>
inline constexpr auto kElevationLabel = make_elevation_label<kAzimuthLabel>();

}  // namespace rotord::settings::detail

/// The label column of an elevation row in the row array (settings.cpp).
#define ROTORD_ELEVATION_LABEL(label) (::rotord::settings::detail::kElevationLabel<label>.data())
