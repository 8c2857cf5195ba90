#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "axis/axis.hpp"
#include "settings/settings.hpp"
#include "util/axis_id.hpp"
#include "util/time.hpp"

namespace rotord {

/// Self-commissioning of one axis (docs/commissioning.md): at creep speed
/// with stall detection tightened it checks the drive's direction against
/// the sensor, finds both end stops, measures speed per drive level, coast,
/// backlash and sensor noise, and proposes settings. Nothing is written
/// until the owner accepts (apply_proposal). Runs from the control tick:
/// fixed-size members, no heap, no exceptions.
class Commissioning {
 public:
  /// kBearing moves nothing: an absolute sensor's zero from the bearing the
  /// antenna points at now, which the owner gives (bearing_deg).
  enum class Step : std::uint8_t { kAll, kDirection, kEnds, kSpeeds, kBearing };
  enum class State : std::uint8_t { kIdle, kRunning, kDone, kAborted };

  struct Request {
    AxisId axis = AxisId::kAz;
    Step step = Step::kAll;
    /// Where the end stops (or limit switches) sit, in degrees: the model's
    /// travel unless the owner knows better. Calibration maps them here.
    float ccw_stop_deg = 0.0f;
    float cw_stop_deg = 450.0f;
    /// kBearing: the true bearing (elevation on el) the antenna points at
    /// now, 0 to 360; anything else (NaN: not given) is refused.
    float bearing_deg = -1.0f;
  };

  /// One evidence sample: time since the run began, position (degrees in
  /// the proposed calibration once the ends are known) and speed.
  struct Sample {
    std::int32_t t_ms = 0;
    float deg = 0.0f;
    float speed_deg_s = 0.0f;
  };
  static constexpr std::size_t kMaxSamples = 400;

  struct Measured {
    bool direction_known = false;
    bool swapped = false;  ///< the CW output turns the rotator CCW
    bool ends_known = false;
    float ccw_reading = 0.0f;  ///< sensor at the CCW end (pot: ADC counts, else degrees)
    float cw_reading = 0.0f;
    float noise_deg = 0.0f;  ///< standard deviation at rest
    bool speeds_known = false;
    float creep_deg_s = 0.0f;  ///< at speed 1 (the slow level)
    float fast_deg_s = 0.0f;   ///< at speed 100 (= creep on a one-speed relay drive)
    float coast_s = 0.0f;
    float backlash_deg = 0.0f;
    float dead_band = -1.0f;  ///< H-bridge only; -1 = not measured
  };

  struct Proposal {
    settings::Id id;
    double value;
  };
  static constexpr std::size_t kMaxProposals = 20;

  /// Refused (with the reason in `why`) without a sensor or with a latched
  /// fault; the controller refuses it while tracking.
  Error start(const Request& request, Axis& axis, const char** why);
  /// Runs one step of the state machine after the axis's own tick.
  void tick(Millis now, Axis& axis);
  /// STOP, a fault elsewhere, a settings change: stops the axis, restores
  /// its configuration and reports why.
  void abort(Axis& axis, const char* reason);
  bool running() const { return state_ == State::kRunning; }
  AxisId axis() const { return req_.axis; }

  State state() const { return state_; }
  const char* phase_name() const;
  const char* reason() const { return reason_; }
  const Request& request() const { return req_; }
  const Measured& measured() const { return m_; }
  std::size_t sample_count() const { return samples_n_; }
  const Sample& sample(std::size_t n) const { return samples_[n]; }
  std::size_t proposal_count() const { return proposals_n_; }
  const Proposal& proposal(std::size_t n) const { return proposals_[n]; }
  /// The proposed values on a scratch copy, checked for consistency, then
  /// copied into `s`; nothing changes on a rejection.
  settings::Rejection apply_proposal(settings::Settings& s) const;
  /// The CW and CCW outputs turn the wrong way: accepting swaps their pins.
  bool proposes_swap() const { return state_ == State::kDone && m_.swapped; }
  /// An evidence sample's position and speed in calibrated degrees.
  float sample_deg(std::size_t n) const { return to_deg(samples_[n].deg); }
  float sample_speed_deg_s(std::size_t n) const { return samples_[n].speed_deg_s * deg_per_unit(); }

 private:
  enum class Phase : std::uint8_t {
    kNoise,
    kNudge1,
    kNudge2,
    kSeekCcw,
    kApproachCw,  ///< an absolute sensor: fast to a margin short of the CW end
    kSeekCw,
    kPrime,
    kRunReverse,
    kRunSame,
    kRunFast,
    kFinished
  };
  /// One jog with its line fit (position against time once the motor runs).
  struct Run {
    bool commanded = false;
    bool stopping = false;
    Millis on_at = -1;  // first tick in kMoving
    Millis stop_at = 0;
    float start_x = 0.0f;
    float cut_x = 0.0f;
    Millis cut_at = 0;
    bool cut_seen = false;
    int rest_n = 0;
    float rest_sum = 0.0f;
    double n = 0, st = 0, sx = 0, stt = 0, stx = 0;
    void clear() { *this = Run{}; }
    float slope() const;
    float intercept() const;
  };

  void enter(Phase phase, Millis now);
  void next_after(Phase done, Millis now, Axis& axis);
  void tick_run(Millis now, Axis& axis);
  float reading(const Axis& axis) const;
  float sensor_lag_s() const;
  float to_deg(float x) const;
  float deg_per_unit() const;
  void record(Millis now, const Axis& axis);
  void finish(Axis& axis);
  void propose(const AxisConfig& base);
  Error propose_bearing(const Request& request, const Axis& axis, const char** why);
  void add(settings::Id id, double value);

  Request req_;
  State state_ = State::kIdle;
  Phase phase_ = Phase::kFinished;
  const char* reason_ = "";
  AxisConfig saved_;
  bool pot_ = false;
  float cal_a_ = 0.0f, cal_b_ = 1.0f;  // frame deg = a + b * counts (pot)
  Millis started_at_ = 0, phase_at_ = 0, last_sample_at_ = 0;
  Millis sample_every_ms_ = 250;
  Millis last_tick_at_ = -1;
  Millis tick_ms_ = 10;
  Direction dir_ = Direction::kNone;  // logical direction of the current jog
  int level_pct_ = 1;
  Run run_;
  float nudge_dx_[2] = {0.0f, 0.0f};
  Direction nudge_dir_[2] = {Direction::kCw, Direction::kCcw};
  double noise_n_ = 0, noise_mean_ = 0, noise_m2_ = 0;
  float noise_frame_ = 0.0f;     // noise at rest in the commissioning frame
  float approach_until_ = 0.0f;  // kApproachCw ends at this reading
  float tau_reverse_s_ = 0.0f;
  float coast_sum_ = 0.0f;
  int coast_count_ = 0;
  Measured m_;
  std::array<Sample, kMaxSamples> samples_{};
  std::size_t samples_n_ = 0;
  std::array<Proposal, kMaxProposals> proposals_{};
  std::size_t proposals_n_ = 0;
};

const char* commissioning_state_name(Commissioning::State state);
/// "all", "direction", "ends", "speeds", "bearing"; false when the name is unknown.
bool parse_commissioning_step(const char* name, std::size_t len, Commissioning::Step& out);

}  // namespace rotord
