#pragma once
#include <array>
#include <cstddef>
#include <span>
#include <string_view>

namespace rotord::protocol {

/// One part of a flat XML message: an element `<name>value</name>`, or
/// (name empty) bare text between elements, as PstRotator's `AZ?` query.
struct XmlItem {
  std::string_view name;
  std::string_view value;  ///< trimmed, entities still escaped
  /// The element held elements (only `nestable`'s may): `value` is its raw
  /// content, to be read with FlatXml::parse_content().
  bool nested = false;
};

/// The one-level XML both UDP rotor formats use (`<N1MMRotor>`, `<PST>`):
/// `[<?xml ...?>] <root> items </root>`, whitespace allowed between the
/// parts. Hand-written rather than a library's: it must run in the Pico's
/// fixed memory, and these messages have no nesting, attributes or CDATA;
/// anything such is refused as malformed rather than guessed at. Names
/// compare case-insensitively. Views point into the datagram.
class FlatXml {
 public:
  static constexpr std::size_t kMaxItems = 12;

  /// False when `message` is not that shape with this root, or holds more
  /// than kMaxItems parts. An element named `nestable` may hold one level of
  /// flat elements instead of text (N1MM+'s `<stop><rotor>..</rotor></stop>`).
  bool parse(std::string_view message, std::string_view root, std::string_view nestable = {});
  /// The parts of a nested item's value: flat elements and text, no root.
  bool parse_content(std::string_view content);
  std::span<const XmlItem> items() const { return {items_.data(), count_}; }

 private:
  /// Reads parts from `s` up to `</root>` (root empty: to the end of `s`).
  bool parse_items(std::string_view& s, std::string_view root, std::string_view nestable);

  std::array<XmlItem, kMaxItems> items_{};
  std::size_t count_ = 0;
};

/// XML text `escaped` with &amp; &lt; &gt; &quot; &apos; replaced, into
/// `out`; the length, or npos for any other entity or when it does not fit.
std::size_t xml_unescape(std::string_view escaped, char* out, std::size_t capacity);

}  // namespace rotord::protocol
