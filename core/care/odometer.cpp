#include "care/odometer.hpp"

#include <cmath>

namespace rotord::care {
namespace {

// The relays of a drive (the PWM channels are an H-bridge's transistors,
// which do not wear by the switching).
constexpr OutputChannel kRelays[] = {OutputChannel::kRelayCw, OutputChannel::kRelayCcw,
                                     OutputChannel::kSpeedFast, OutputChannel::kBrake,
                                     OutputChannel::kVoltageFast};

/// Where the motor is driven: its direction, or kNone.
Direction driven(const DriveOutputs& o) {
  if (o.on(OutputChannel::kRelayCw) || o.on(OutputChannel::kPwmCw)) return Direction::kCw;
  if (o.on(OutputChannel::kRelayCcw) || o.on(OutputChannel::kPwmCcw)) return Direction::kCcw;
  return Direction::kNone;
}

/// The axis turns by the motor: driven, or coasting out after the cut.
bool turning(const AxisStatus& s) {
  return s.state == AxisState::kStarting || s.state == AxisState::kMoving ||
         s.state == AxisState::kStopping || s.state == AxisState::kReversing;
}

std::uint64_t sum(const AxisWear& w) {
  std::uint64_t total =
      w.starts + w.reversals + w.run_ms + w.turned_deg + w.brake_cycles + w.relay_switchings;
  return total + w.faults_total();
}

}  // namespace

std::uint32_t AxisWear::faults_total() const {
  std::uint32_t total = 0;
  for (std::size_t n = 1; n < faults.size(); ++n) total += faults[n];
  return total;
}

void AxisOdometer::observe(const AxisStatus& s, Millis now) {
  if (!s.present) return;
  if (!seen_) {
    // The first tick: every output was off before it (Controller::begin),
    // so a go-to given before it still counts its start.
    seen_ = true;
    last_now_ = now;
  }
  const Direction was = driven(last_out_);
  const Direction is = driven(s.outputs);
  if (is != Direction::kNone && is != was) {
    ++wear_.starts;
    if (last_start_dir_ != Direction::kNone && is != last_start_dir_) ++wear_.reversals;
    last_start_dir_ = is;
    close_segment(s);  // a reversal: the last drive's turn ends here
    if (s.position_valid) {
      segment_open_ = true;
      segment_from_deg_ = s.position_deg;
    }
  }
  if (was != Direction::kNone && now > last_now_)
    wear_.run_ms += static_cast<std::uint64_t>(now - last_now_);
  for (const OutputChannel ch : kRelays)
    if (s.outputs.on(ch) && !last_out_.on(ch)) ++wear_.relay_switchings;
  if (s.outputs.on(OutputChannel::kBrake) && !last_out_.on(OutputChannel::kBrake))
    ++wear_.brake_cycles;
  if (s.fault != last_fault_ && s.fault != AxisFault::kNone)
    ++wear_.faults[static_cast<std::size_t>(s.fault)];
  // Degrees: from where a drive started to where the axis came to rest
  // after it (the coast included); summing every tick's step instead would
  // count the sensor's noise, tens of degrees an hour of running.
  if (segment_open_ && !turning(s) && is == Direction::kNone) close_segment(s);
  last_out_ = s.outputs;
  last_fault_ = s.fault;
  last_now_ = now;
}

void AxisOdometer::close_segment(const AxisStatus& s) {
  if (!segment_open_) return;
  segment_open_ = false;
  if (!s.position_valid) return;  // no reading at the end: the turn is not known
  carry_deg_ += std::fabs(s.position_deg - segment_from_deg_);
  if (carry_deg_ >= 1.0f) {
    const float whole = std::floor(carry_deg_);
    wear_.turned_deg += static_cast<std::uint32_t>(whole);
    carry_deg_ -= whole;
  }
}

void AxisOdometer::restore(const AxisWear& wear) {
  wear_ = wear;
  carry_deg_ = 0.0f;
}

void Odometer::observe(const AxisStatus& az, const AxisStatus& el, Millis now) {
  axes_[0].observe(az, now);
  axes_[1].observe(el, now);
  const std::uint64_t total = sum(axes_[0].wear()) + sum(axes_[1].wear());
  if (total != summary_) {
    summary_ = total;
    ++revision_;
  }
}

void Odometer::restore(const AxisWear& az, const AxisWear& el, std::int64_t reset_unix_s) {
  axes_[0].restore(az);
  axes_[1].restore(el);
  reset_unix_s_ = reset_unix_s;
  summary_ = sum(az) + sum(el);
}

void Odometer::reset(std::int64_t unix_s) {
  summary_ = 0;
  for (AxisOdometer& a : axes_) a.restore(AxisWear{});
  reset_unix_s_ = unix_s;
  ++revision_;
  ++resets_;
}

}  // namespace rotord::care
