#include "usb_personality.hpp"

#include <new>

#include "settings/settings.hpp"

namespace rotord::usb_port {

std::optional<protocol::Personality> personality_from_setting(int value) {
  const settings::Id id = settings::Id::kUsbPersonality;
  if (value < 0 || value >= settings::choice_count(id)) return std::nullopt;
  const protocol::ProtocolInfo* p = protocol::find_protocol(settings::choice_name(id, value));
  if (p == nullptr) return std::nullopt;
  return p->personality;
}

const char* personality_name(std::optional<protocol::Personality> personality) {
  // The registry's names are string literals: NUL-terminated.
  return personality ? protocol::protocol_info(*personality).name.data() : "off";
}

void PersonalitySessions::end() {
  if (live_ != nullptr) live_->~Session();
  live_ = nullptr;
}

protocol::Session& PersonalitySessions::renew() {
  if (!personality_) return silent_;
  // The previous session goes first, then the new one is built in place
  // (make() returns a prvalue: no copy, no temporary on the stack).
  end();
  live_ = protocol::with_session_type(*personality_, [this](auto session) -> protocol::Session* {
    using S = typename decltype(session)::type;
    return ::new (static_cast<void*>(storage_)) S(decltype(session)::make(deps_));
  });
  return *live_;
}

}  // namespace rotord::usb_port
