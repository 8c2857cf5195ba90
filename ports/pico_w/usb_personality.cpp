#include "usb_personality.hpp"

namespace rotord::usb_port {

Personality personality_from_setting(int value) {
  if (value < 0 || value >= kPersonalityCount) return Personality::kOff;
  return static_cast<Personality>(value);
}

const char* personality_name(Personality personality) {
  switch (personality) {
    case Personality::kOff:
      break;
    case Personality::kGs232:
      return "Yaesu GS-232";
    case Personality::kEasycomm:
      return "Easycomm II/III";
    case Personality::kSeed:
      return "seed $cmd protocol";
    case Personality::kWrc:
      return "WRC text protocol";
    case Personality::kRotctld:
      return "Hamlib rotctld";
  }
  return "off";
}

protocol::Session& PersonalitySessions::renew() {
  // emplace destroys the previous session first, then builds in place: the
  // sessions hold a Controller& and need not be movable.
  switch (personality_) {
    case Personality::kOff:
      break;
    case Personality::kGs232:
      return session_.emplace<protocol::Gs232Session>(controller_);
    case Personality::kEasycomm:
      return session_.emplace<protocol::EasycommSession>(controller_, version_);
    case Personality::kSeed:
      return session_.emplace<protocol::SeedSession>(controller_);
    case Personality::kWrc:
      return session_.emplace<protocol::WrcSession>(controller_, version_);
    case Personality::kRotctld:
      return session_.emplace<protocol::RotctldSession>(controller_, version_);
  }
  return session_.emplace<Silent>();
}

}  // namespace rotord::usb_port
