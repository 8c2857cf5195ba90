#include "rotator/stream_lead.hpp"

namespace rotord {

void StreamLead::Axis::note(float sent_deg) {
  if (have) {
    const float d = sent_deg - last_deg;
    step_deg = d < 0.0f ? -d : d;
    // Steps below the clients' two decimals do not say a direction.
    const int sign = d > 0.005f ? 1 : (d < -0.005f ? -1 : 0);
    if (sign != 0) {
      steady = sign == dir ? steady + 1 : 1;
      dir = sign;
    }
  }
  have = true;
  last_deg = sent_deg;
}

StreamLead::Plan StreamLead::plan(float sent_deg, float pos_deg, int dir, bool at_rest,
                                  float band_deg, float min_deg, float max_deg) {
  Plan p;
  p.aim_deg = sent_deg;
  if (dir == 0) return p;
  const float lead = kLeadOfBand * band_deg;
  // How far the target is ahead of the antenna in the direction of motion.
  const float ahead = (sent_deg - pos_deg) * static_cast<float>(dir);
  // Standing within the band around the target (the antenna led it and the
  // target has not yet passed it by a band): no start.
  if (at_rest && ahead <= band_deg && ahead >= -(lead + band_deg)) {
    p.hold = true;
    return p;
  }
  const float aim = sent_deg + static_cast<float>(dir) * lead;
  // Never past the travel: the lead is cut at its ends.
  p.aim_deg = aim < min_deg ? min_deg : (aim > max_deg ? max_deg : aim);
  if ((p.aim_deg - sent_deg) * static_cast<float>(dir) < 0.0f) p.aim_deg = sent_deg;
  return p;
}

}  // namespace rotord
