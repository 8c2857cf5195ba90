#pragma once
#include <cstddef>
#include <cstring>
#include <string_view>

#include "util/byte_sink.hpp"

namespace rotord {

/// A ByteSink over a caller's fixed buffer: what does not fit is dropped and
/// remembered (overflowed), so a too-long document or message is refused,
/// never cut. The settings file, the odometer's record and the MQTT
/// messages are written through it.
class FixedSink final : public ByteSink {
 public:
  FixedSink(char* buf, std::size_t cap) : buf_(buf), cap_(cap) {}
  void write(std::string_view bytes) override {
    if (bytes.size() > cap_ - len_) {
      overflowed_ = true;
      return;
    }
    std::memcpy(buf_ + len_, bytes.data(), bytes.size());
    len_ += bytes.size();
  }
  std::string_view view() const { return {buf_, len_}; }
  bool overflowed() const { return overflowed_; }
  void clear() {
    len_ = 0;
    overflowed_ = false;
  }

 private:
  char* buf_;
  std::size_t cap_;
  std::size_t len_ = 0;
  bool overflowed_ = false;
};

}  // namespace rotord
