#pragma once

#include "motion/angles.hpp"

namespace rotord {

/// The azimuth frame one client uses, decided per session. A tracker that
/// sends 0..360 and whose go-to the continuity rule put on another turn
/// (Gpredict sent 0.5, the antenna goes to 360.5 on a 450 deg rotator) must
/// not read back a position 360 deg away from what it sent: Gpredict would
/// re-send every cycle. Such a session reads the position on the turn
/// nearest what it last sent (360.5 reads 0.5); a session whose go-tos were
/// taken literally reads the unwrapped position, as before.
class ClientFrame {
 public:
  /// A go-to of this session was obeyed: `sent_az_deg` as the client sent
  /// it, `shift_deg` what the continuity rule added
  /// (Controller::az_continuity_shift_deg()).
  void note_goto(float sent_az_deg, float shift_deg) {
    shifted_ = shift_deg != 0.0f;
    sent_az_deg_ = sent_az_deg;
  }
  /// The rotator's unwrapped azimuth in this client's frame.
  float az_deg(float position_deg) const {
    return shifted_ ? unwrap_near(position_deg, sent_az_deg_) : position_deg;
  }
  bool shifted() const { return shifted_; }

 private:
  bool shifted_ = false;
  float sent_az_deg_ = 0.0f;
};

}  // namespace rotord
