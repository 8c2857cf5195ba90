// The wind stow's part of the controller (docs/care.md, "Wind stow"): the
// readings in, the stow move out. Runs in the control tick: fixed members
// only, no heap.
#include <cmath>

#include "motion/angles.hpp"
#include "rotator/controller.hpp"

namespace rotord {

using settings::Id;

namespace {

/// wind.mqtt_unit's choices (m/s|km/h|mph|kn) to m/s.
float unit_to_mps(int unit) {
  switch (unit) {
    case 1:
      return 1.0f / 3.6f;
    case 2:
      return 0.44704f;
    case 3:
      return 0.514444f;
    default:
      return 1.0f;
  }
}

}  // namespace

care::WindConfig Controller::wind_config() const {
  care::WindConfig c;
  const int source = settings_.i(Id::kWindSource);
  c.source = source == 1   ? care::WindSource::kMqtt
             : source == 2 ? care::WindSource::kPulses
                           : care::WindSource::kOff;
  c.stow_mps = settings_.f(Id::kWindStowMps);
  c.calm_mps = settings_.f(Id::kWindCalmMps);
  c.hold_ms = static_cast<Millis>(settings_.i(Id::kWindHoldS)) * 1000;
  c.calm_ms = static_cast<Millis>(settings_.i(Id::kWindCalmMin)) * 60000;
  c.override_ms = static_cast<Millis>(settings_.i(Id::kWindOverrideMin)) * 60000;
  c.into_wind = settings_.b(Id::kWindIntoWind);
  return c;
}

void Controller::wind_speed_message(std::string_view payload) {
  if (wind_.config().source != care::WindSource::kMqtt) return;
  wind_.speed_text(payload, unit_to_mps(settings_.i(Id::kWindMqttUnit)), now_);
}

void Controller::wind_direction_message(std::string_view payload) {
  // A direction serves either source (a vane beside a pulse anemometer).
  if (wind_.config().source == care::WindSource::kOff) return;
  wind_.direction_text(payload, now_);
}

Error Controller::wind_override(int minutes) {
  if (minutes < 0 || minutes > 1440) return Error::kOutOfRange;
  if (!wind_.override_now(now_, static_cast<Millis>(minutes) * 60000)) return Error::kNotFound;
  // What the stow was doing stops: the operator takes over from here.
  stow_pending_ = false;
  if (mode_ == Mode::kStow) {
    az_.stop();
    el_.stop();
    mode_ = Mode::kIdle;
  }
  return Error::kOk;
}

void Controller::end_wind_override() {
  wind_.end_override();
}

float Controller::wind_stow_az_deg() const {
  if (wind_.config().into_wind && wind_.has_fresh_direction(now_)) {
    // The boom into the wind: the azimuth the wind comes from, on the turn
    // the travel allows that is nearest; unreachable (a travel short of a
    // circle), the stow heading.
    if (const std::optional<float> az = resolve_az(wind_.direction_deg(), AzTarget::kCompass))
      return *az;
  }
  const float stow = settings_.f(Id::kWindStowAzDeg);
  return az_.config().continuous ? wrap_360(stow) : stow;
}

void Controller::tick_wind(Millis now) {
  if (wind_.config().source == care::WindSource::kPulses && wind_pulses_ != nullptr) {
    const std::optional<float> mps =
        wind_meter_.sample(wind_pulses_->count(), now, settings_.f(Id::kWindPulsesPerMps));
    if (mps) wind_.speed(*mps, now);
  }
  wind_.tick(now);
  if (wind_.take_stow_request()) stow_pending_ = true;
  if (!wind_.refusing()) stow_pending_ = false;
  if (!stow_pending_ || estop_active_) return;
  // The stow takes over from whatever was going on: a track, a recognised
  // pass, a client's stream, self-commissioning.
  if (commissioning_.running()) commissioning_.abort(commissioned_axis(), "wind stow");
  end_track();
  stream_.interrupt();
  // A latched fault refuses the move: tried again each tick (a RESET lets
  // it through).
  if (az_.status().fault != AxisFault::kNone || (has_el_ && el_.status().fault != AxisFault::kNone))
    return;
  if (az_.go_to(wind_stow_az_deg()) != Error::kOk) return;
  if (has_el_) el_.go_to(settings_.f(Id::kParkElDeg));
  stow_pending_ = false;
  mode_ = Mode::kStow;
  last_activity_ms_ = now;
}

}  // namespace rotord
