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
  /// than kMaxItems parts.
  bool parse(std::string_view message, std::string_view root);
  std::span<const XmlItem> items() const { return {items_.data(), count_}; }

 private:
  std::array<XmlItem, kMaxItems> items_{};
  std::size_t count_ = 0;
};

/// XML text `escaped` with &amp; &lt; &gt; &quot; &apos; replaced, into
/// `out`; the length, or npos for any other entity or when it does not fit.
std::size_t xml_unescape(std::string_view escaped, char* out, std::size_t capacity);

}  // namespace rotord::protocol
