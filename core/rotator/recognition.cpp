#include "rotator/recognition.hpp"

namespace rotord {

const char* recognition_end_name(RecognitionEnd why) {
  switch (why) {
    case RecognitionEnd::kNone:
      return "none";
    case RecognitionEnd::kDeparted:
      return "departed";
    case RecognitionEnd::kStop:
      return "stop";
    case RecognitionEnd::kPark:
      return "park";
    case RecognitionEnd::kOtherSource:
      return "other_source";
    case RecognitionEnd::kCommand:
      return "command";
    case RecognitionEnd::kLos:
      return "los";
    case RecognitionEnd::kFailed:
      return "failed";
    case RecognitionEnd::kOff:
      return "off";
  }
  return "?";
}

}  // namespace rotord
