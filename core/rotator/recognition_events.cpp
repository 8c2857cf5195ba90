#include "rotator/recognition_events.hpp"

#include <cstdio>

namespace rotord {

bool RecognitionEvents::next(const Recognition& now, char* line, std::size_t capacity) {
  if (capacity == 0) return false;
  if (begun_ != now.begun) {
    begun_ = now.begun;
    if (now.catalog != 0) {
      std::snprintf(line, capacity,
                    "recognised %s (NORAD %u) in a client's go-to stream: following its pass",
                    now.name, static_cast<unsigned>(now.catalog));
    } else {
      std::snprintf(line, capacity,
                    "recognised the %s in a client's go-to stream: following its pass", now.name);
    }
    return true;
  }
  if (endings_ != now.endings) {
    endings_ = now.endings;
    std::snprintf(line, capacity, "recognised pass of %s ended: %s", now.name,
                  recognition_end_name(now.ended));
    return true;
  }
  return false;
}

}  // namespace rotord
