#pragma once
#include <cstddef>
#include <cstdint>

#include "rotator/recognition.hpp"

namespace rotord {

/// What the log should say about recognised passes since it last asked: a
/// recognition begun (the object, NORAD number) and one ended (why). The
/// ports ask from their main loop, as for AxisEvents. No heap.
class RecognitionEvents {
 public:
  /// Takes the counts as they are now: only later events are told.
  void begin(const Recognition& now) {
    begun_ = now.begun;
    endings_ = now.endings;
  }
  /// Writes the next event into `line` (NUL-terminated), or returns false
  /// when there is none. Call until false.
  bool next(const Recognition& now, char* line, std::size_t capacity);

 private:
  std::uint32_t begun_ = 0;
  std::uint32_t endings_ = 0;
};

}  // namespace rotord
