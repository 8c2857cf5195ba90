#pragma once
#include <array>
#include <cstddef>
#include <string_view>

namespace rotord::protocol {

/// Splits a byte stream into lines ended by CR, LF or CRLF, in a fixed buffer.
/// A line longer than Capacity is reported once as overflowing and its bytes
/// are dropped up to the next line end, so a 1 MB line costs no memory.
template <std::size_t Capacity>
class LineAssembler {
 public:
  /// on_line(std::string_view line, bool overflowed) runs for every complete
  /// line, including empty ones (callers usually ignore those).
  template <typename OnLine>
  void feed(std::string_view bytes, OnLine&& on_line) {
    for (char c : bytes) {
      if (c == '\r' || c == '\n') {
        if (c == '\n' && last_was_cr_) {
          last_was_cr_ = false;
          continue;  // CRLF is one line end
        }
        last_was_cr_ = c == '\r';
        on_line(std::string_view(buf_.data(), overflowed_ ? 0 : length_), overflowed_);
        length_ = 0;
        overflowed_ = false;
        continue;
      }
      last_was_cr_ = false;
      if (overflowed_) continue;
      if (length_ == Capacity) {
        overflowed_ = true;
        continue;
      }
      buf_[length_++] = c;
    }
  }

  std::size_t pending() const { return length_; }
  static constexpr std::size_t capacity() { return Capacity; }

 private:
  std::array<char, Capacity> buf_{};
  std::size_t length_ = 0;
  bool overflowed_ = false;
  bool last_was_cr_ = false;
};

}  // namespace rotord::protocol
