#pragma once
// Which byte session the Pico W serves on its USB protocol port
// (usb.personality), built in one piece of static storage.
//
// Portable (no pico-sdk include), so tests/usb runs it on the host.
#include <cstdint>
#include <variant>

#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "usb_cdc_link.hpp"

namespace rotord::usb_port {

/// The values of usb.personality, in the order of its choices.
enum class Personality : std::uint8_t { kOff, kGs232, kEasycomm, kSeed, kWrc, kRotctld };

inline constexpr int kPersonalityCount = 6;
/// The choices string of usb.personality, checked against the table by the tests.
inline constexpr const char* kPersonalityChoices = "off|gs232|easycomm|seed|wrc|rotctld";

/// The setting's value as a personality; out of range is kOff.
Personality personality_from_setting(int value);
/// For logs and the USB interface name, e.g. "Yaesu GS-232"; "off" for kOff.
const char* personality_name(Personality personality);

/// Builds the session of one personality in place, each time anew. Storage
/// for the largest session only (rotctld, ~2.6 KB), not for all five.
class PersonalitySessions final : public SessionMaker {
 public:
  PersonalitySessions(Personality personality, Controller& controller, const char* version)
      : personality_(personality), controller_(controller), version_(version) {}
  PersonalitySessions(const PersonalitySessions&) = delete;
  PersonalitySessions& operator=(const PersonalitySessions&) = delete;

  protocol::Session& renew() override;
  Personality personality() const { return personality_; }

 private:
  /// kOff: a session that ignores everything (the firmware builds no link
  /// then; this only keeps renew() total).
  class Silent final : public protocol::Session {
   public:
    void receive(std::string_view, protocol::ByteSink&) override {}
  };

  Personality personality_;
  Controller& controller_;
  const char* version_;
  std::variant<std::monostate, Silent, protocol::Gs232Session, protocol::EasycommSession,
               protocol::SeedSession, protocol::WrcSession, protocol::RotctldSession>
      session_;
};

}  // namespace rotord::usb_port
