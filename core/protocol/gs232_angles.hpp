#pragma once
#include <cstdint>
#include <optional>

#include "rotator/controller.hpp"

namespace rotord::protocol::gs232 {

/// The azimuth scale a GS-232 speaks: 0..360, or 0..450 on overlap rotators
/// (GS-232A: DIP switch 5; GS-232B: P36 / P45).
enum class AzRange : std::uint8_t { k360, k450 };

inline int full_scale_deg(AzRange range) {
  return range == AzRange::k450 ? 450 : 360;
}

/// The scale from gs232.az_range; "auto" is 450 when the travel reaches past
/// 360 deg (a G-5500) and 360 otherwise, like the DIP switch an installer sets.
AzRange az_range(const settings::Settings& settings, const Limits& limits);

/// The whole degrees a GS-232 reports for an unwrapped azimuth: the position
/// itself while it lies on the scale (0..360 or 0..450), otherwise its compass
/// bearing 0..359 (a south-stop rotator at -10 reports 350, a 450 deg rotator
/// at 400 reports 40 on the 360 scale). The reply formats have no sign.
int report_az_deg(float unwrapped_deg, AzRange range, bool continuous);

/// Elevation in whole degrees, clamped to 0..180: the A format `+0eee` has no
/// sign and Hamlib's 601 backend rejects `-0005`.
int report_el_deg(float el_deg);

/// Where Controller::go_to should send an azimuth the client gave on the
/// GS-232 scale (already checked to be 0..full scale).
struct AzGoal {
  float az_deg;
  AzTarget mode;
};

/// A GS-232 angle counts from the counter-clockwise stop, like the pot of the
/// real controller: taken as the unwrapped position when the travel contains
/// it (M010 on a G-5500 at 350 turns back to 10, as the real one does). An
/// angle outside the travel (350 on a -180..180 south-stop rotator, 400 on a
/// 0..360 one) is the compass bearing it names, reached by the shortest turn
/// inside the travel. Either way the controller never drives past its limits.
AzGoal az_goal(int gs232_deg, const Limits& limits);

}  // namespace rotord::protocol::gs232
