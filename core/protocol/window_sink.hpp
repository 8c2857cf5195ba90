#pragma once
// A reply longer than a transport can take at once, sent in windows: the
// session writes the whole reply again each time (it keeps no copy: the
// Pico has no RAM for a 41 KB JSON schema), and this sink lets through only
// the bytes after those already sent, as many as fit. Used by the console's
// listings and the HTTP session's long GET responses
// (protocol::Session::output_pending / write_more).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "util/byte_sink.hpp"
#include "util/slice.hpp"

namespace rotord::protocol {

class WindowSink final : public ByteSink {
 public:
  /// Writes of the reply that do not fit whole: kWhole ends the window before
  /// the first one (a listing's lines are never cut, except one longer than
  /// the whole room, so that every window makes progress); kBytes cuts it.
  enum class Cut : std::uint8_t { kWhole, kBytes };

  /// `skip`: bytes of the reply already sent; `room`: the most to send now.
  /// Less is sent when `out.room()` says the transport takes less.
  /// `sent_hash`: sent_hash() of the window before; when given and the
  /// skipped bytes hash otherwise, the reply has changed since and nothing
  /// is let through (mismatch()).
  WindowSink(ByteSink& out, std::size_t skip, std::size_t room, Cut cut,
             std::optional<std::uint32_t> sent_hash = std::nullopt)
      : out_(out), skip_(skip), room_(room), cut_(cut), expected_hash_(sent_hash) {}
  WindowSink(const WindowSink&) = delete;
  WindowSink& operator=(const WindowSink&) = delete;

  void write(std::string_view bytes) override {
    total_ += bytes.size();
    if (skip_ > 0) {
      const std::string_view skipped = text::slice(bytes, 0, skip_);
      skipped_hash_ = hash(skipped, skipped_hash_);
      skip_ -= skipped.size();
      bytes = text::slice(bytes, skipped.size());
      sent_hash_ = skipped_hash_;
    }
    if (bytes.empty() || full_) return;
    if (expected_hash_ && skipped_hash_ != *expected_hash_) {
      mismatch_ = full_ = true;
      return;
    }
    const std::size_t room = std::min(room_, out_.room());
    if (bytes.size() > room) {
      full_ = true;
      if (cut_ == Cut::kWhole && written_ > 0) return;
      bytes = text::slice(bytes, 0, room);
    }
    room_ -= bytes.size();
    written_ += bytes.size();
    sent_hash_ = hash(bytes, sent_hash_);
    out_.write(bytes);  // as the reply wrote it: one unit, or its cut end
  }
  std::size_t room() const override { return std::min(room_, out_.room()); }

  /// The whole reply's length (the window's reply was written to the end).
  std::size_t total() const { return total_; }
  std::size_t written() const { return written_; }
  /// The bytes skipped were not those sent before (see the constructor).
  bool mismatch() const {
    return mismatch_ || (expected_hash_ && skip_ == 0 && skipped_hash_ != *expected_hash_);
  }
  /// FNV-1a of the bytes skipped, and of those and the ones let through: a
  /// session that cannot be sure it writes the same reply again compares the
  /// skipped bytes' hash with sent_hash() of the window before.
  std::uint32_t skipped_hash() const { return skipped_hash_; }
  std::uint32_t sent_hash() const { return sent_hash_; }
  static constexpr std::uint32_t kHashStart = 2166136261u;
  static std::uint32_t hash(std::string_view bytes, std::uint32_t h) {
    for (char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
    return h;
  }

 private:
  ByteSink& out_;
  std::size_t skip_;
  std::size_t room_;
  Cut cut_;
  std::optional<std::uint32_t> expected_hash_;
  bool mismatch_ = false;
  bool full_ = false;
  std::size_t total_ = 0;
  std::size_t written_ = 0;
  std::uint32_t skipped_hash_ = kHashStart;
  std::uint32_t sent_hash_ = kHashStart;
};

}  // namespace rotord::protocol
