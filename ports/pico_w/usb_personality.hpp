#pragma once
// Which byte session the Pico W serves on its USB protocol port
// (usb.personality), built in one piece of static storage.
//
// Portable (no pico-sdk include), so tests/usb runs it on the host.
#include <optional>

#include "protocol/protocol_registry.hpp"
#include "usb_cdc_link.hpp"

namespace rotord::usb_port {

/// usb.personality as a protocol of the registry (core/protocol/
/// protocol_registry.hpp): its choices are "off" and the registry's keys
/// (checked by tests/usb); nullopt for off or a value out of range.
std::optional<protocol::Personality> personality_from_setting(int value);
/// For logs and the USB interface name, e.g. "Yaesu GS-232"; "off" for none.
const char* personality_name(std::optional<protocol::Personality> personality);

/// Builds the session of one personality in place, each time anew. Storage
/// for the largest session only (rotctld, ~2.6 KB), not for all five.
class PersonalitySessions final : public SessionMaker {
 public:
  /// `console`: what the console needs from the port, should usb.personality
  /// be the console.
  PersonalitySessions(std::optional<protocol::Personality> personality, Controller& controller,
                      const char* version, const protocol::ConsolePort* console = nullptr)
      : personality_(personality), deps_{controller, version, nullptr, console} {}
  ~PersonalitySessions() { end(); }
  PersonalitySessions(const PersonalitySessions&) = delete;
  PersonalitySessions& operator=(const PersonalitySessions&) = delete;

  protocol::Session& renew() override;
  std::optional<protocol::Personality> personality() const { return personality_; }

 private:
  /// Off: a session that ignores everything (the firmware builds no link
  /// then; this only keeps renew() total).
  class Silent final : public protocol::Session {
   public:
    void receive(std::string_view, protocol::ByteSink&) override {}
  };

  void end();

  std::optional<protocol::Personality> personality_;
  protocol::SessionDeps deps_;
  alignas(protocol::kAnySessionAlign) unsigned char storage_[protocol::kAnySessionBytes];
  protocol::Session* live_ = nullptr;  ///< built in storage_, or nullptr
  Silent silent_;
};

}  // namespace rotord::usb_port
