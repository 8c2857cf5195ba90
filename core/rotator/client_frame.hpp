#pragma once

#include <optional>

#include "motion/angles.hpp"

namespace rotord {

/// The azimuth frame one client uses, decided per session. A tracker that
/// sends 0..360 and whose go-to the continuity rule put on another turn
/// (Gpredict sent 0.5, the antenna goes to 360.5 on a 450 deg rotator) must
/// not read back a position 360 deg away from what it sent: Gpredict would
/// re-send every cycle. Such a session reads the position on the turn
/// nearest what it last sent (360.5 reads 0.5); a session whose go-tos were
/// taken literally reads the unwrapped position, as before. A session whose
/// stream rotord recognised and follows (Controller::last_goto_recognised())
/// reads in its frame too, flip included: the follower's plan may point
/// with el 120 where the client sent 60 (or the reverse), the same place in
/// the sky, and the client must not see a position 180 deg off.
class ClientFrame {
 public:
  /// A go-to of this session was obeyed: `sent_az_deg` as the client sent
  /// it, `shift_deg` what the continuity rule added
  /// (Controller::az_continuity_shift_deg()).
  /// `recognised`: the go-to began or continued a recognised pass, sent
  /// with elevation `sent_el_deg`.
  void note_goto(float sent_az_deg, float shift_deg, bool recognised = false,
                 float sent_el_deg = 0.0f) {
    shifted_ = shift_deg != 0.0f || recognised;
    recognised_ = recognised;
    sent_az_deg_ = sent_az_deg;
    sent_el_deg_ = sent_el_deg;
  }
  /// The rotator's unwrapped azimuth in this client's frame.
  float az_deg(float position_deg) const {
    // Following a recognised pass, a compass client's target is the
    // object's 0..360 azimuth now, not the one it sent minutes ago: a
    // compass reading agrees with it through north too.
    if (recognised_ && sent_az_deg_ >= 0.0f && sent_az_deg_ <= 360.0f)
      return wrap_360(position_deg);
    return shifted_ ? unwrap_near(position_deg, sent_az_deg_) : position_deg;
  }
  /// The rotator's position (unwrapped az, el) in this client's frame.
  /// `object_az_deg`: while a recognised pass is followed, where the object
  /// is now (0..360; Controller::recognised_az_deg()), which is what a
  /// compass client compares the reading with.
  void read(float& az_deg, float& el_deg, std::optional<float> object_az_deg) const {
    if (recognised_ && (el_deg > 90.0f) != (sent_el_deg_ > 90.0f)) {
      az_deg += 180.0f;
      el_deg = 180.0f - el_deg;
    }
    if (recognised_ && object_az_deg && sent_az_deg_ >= 0.0f && sent_az_deg_ <= 360.0f) {
      // The turn nearest the client's own target now (the antenna may be
      // a lag ahead of it across north: 0.3 while the client's is 359.8).
      const float target = sent_el_deg_ > 90.0f ? *object_az_deg + 180.0f : *object_az_deg;
      az_deg = unwrap_near(az_deg, wrap_360(target));
      return;
    }
    az_deg = this->az_deg(az_deg);
  }
  bool shifted() const { return shifted_; }

 private:
  bool shifted_ = false;
  bool recognised_ = false;
  float sent_az_deg_ = 0.0f;
  float sent_el_deg_ = 0.0f;
};

}  // namespace rotord
