#pragma once
#include <cstddef>
#include <cstdio>
#include <string_view>

namespace rotord::protocol::rotctld {

/// Hamlib error codes (enum rig_errcode_e, include/hamlib/rig.h); rotctld
/// sends them negated: `RPRT -1` is RIG_EINVAL.
enum class HamlibError : int {
  kOk = 0,
  kInvalid = 1,         ///< RIG_EINVAL: bad number, out of range, unknown token
  kNotImplemented = 4,  ///< RIG_ENIMPL: a command rotctld does not know
  kIo = 6,              ///< RIG_EIO: no position reading / no raw port
  kRejected = 9,        ///< RIG_ERJCTED: the rotator refuses (fault, limit)
  kNotAvailable = 11,   ///< RIG_ENAVAIL: e.g. elevation on an azimuth-only rotator
};

/// One whole reply, built in a fixed buffer and written with a single
/// ByteSink::write (Gpredict reads each reply with one recv).
class ReplyBuffer {
 public:
  static constexpr std::size_t kCapacity = 1536;  ///< the longest reply is dump_caps

  void append(std::string_view text) {
    for (char c : text) put(c);
  }
  void put(char c) {
    if (length_ < kCapacity) buf_[length_++] = c;
  }
  template <typename... Args>
  void format(const char* fmt, Args... args) {
    const std::size_t room = kCapacity - length_;
    if (room == 0) return;
    const int n = std::snprintf(buf_ + length_, room, fmt, args...);
    if (n < 0) return;
    length_ += static_cast<std::size_t>(n) < room ? static_cast<std::size_t>(n) : room - 1;
  }
  void clear() { length_ = 0; }
  std::string_view view() const { return {buf_, length_}; }

 private:
  char buf_[kCapacity];
  std::size_t length_ = 0;
};

}  // namespace rotord::protocol::rotctld
