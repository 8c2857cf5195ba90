#pragma once
#include <array>
#include <optional>
#include <string_view>

#include "access/control_lock.hpp"
#include "axis/axis.hpp"
#include "care/odometer.hpp"
#include "care/start_ceiling.hpp"
#include "care/wind_pulses.hpp"
#include "care/wind_stow.hpp"
#include "hal/pulse_counter.hpp"
#include "hal/wall_clock.hpp"
#include "rotator/command_journal.hpp"
#include "rotator/commissioning.hpp"
#include "rotator/goto_match.hpp"
#include "rotator/goto_stream.hpp"
#include "rotator/recognition.hpp"
#include "rotator/stream_lead.hpp"
#include "rotator/tracker.hpp"
#include "settings/settings.hpp"
#include "tracking/track_plan.hpp"

namespace rotord {

enum class Mode : std::uint8_t { kIdle, kGoto, kManual, kPark, kTrack, kStow };

const char* mode_name(Mode mode);

/// The travel the rotator may use, as every protocol must report it: the
/// same record the pass planner plans within (one type, not two copies).
using Limits = tracking::Travel;

struct RotatorStatus {
  AxisStatus az;
  AxisStatus el;  ///< present == false on azimuth-only rotators
  Mode mode = Mode::kIdle;
  int speed_pct = 50;
  Limits limits;
  // The wind stow (docs/care.md), for the log and the protocols' status.
  care::WindState wind_state = care::WindState::kOff;
  bool wind_has_speed = false;
  float wind_speed_mps = 0.0f;
  std::uint32_t wind_stows = 0;
  std::uint32_t wind_overrides = 0;
  std::uint32_t wind_rejected = 0;  ///< every reason
  bool any_fault() const { return az.fault != AxisFault::kNone || el.fault != AxisFault::kNone; }
  bool moving() const {
    return (az.state != AxisState::kIdle && az.state != AxisState::kFault) ||
           (el.present && el.state != AxisState::kIdle && el.state != AxisState::kFault);
  }
};

/// How a go-to azimuth is read.
enum class AzTarget : std::uint8_t {
  kCompass,    ///< 0..360 picks the turn within the travel that turns least;
               ///< values outside 0..360 are taken as unwrapped positions
  kUnwrapped,  ///< always an unwrapped position, e.g. 60 on a 450 deg rotator at 400
};

/// The rotator: one or two axes, the command API every protocol uses, and the
/// control tick. Single-threaded by design: ports call commands and tick()
/// from one loop (asio on Linux, the poll loop on the Pico).
class Controller {
 public:
  Controller(settings::Settings& settings, const AxisIo& az_io, const AxisIo& el_io);

  /// All outputs off, first readings. Call once before the first tick.
  void begin(Millis now);
  /// One control step: applies changed settings, reads sensors, steps the
  /// axis state machines, writes outputs. 100 Hz nominal.
  void tick(Millis now);
  /// All outputs off (exit, signal, watchdog).
  void shutdown();
  /// The emergency-stop switch (pins.estop / gpiod.estop), or nullptr. Read
  /// every tick before the axes: active, both axes stop at once and latch
  /// ESTOP. `input` reads true when its contact is closed; which state stops
  /// is estop.normally_closed.
  void attach_estop(hal::DigitalIn* input) { estop_ = input; }
  /// Whether the emergency stop is active now (as of the last tick).
  bool estop_active() const { return estop_active_; }
  /// UTC for tracking (Linux: the system clock, or start UTC + controller
  /// time under the simulator's --speedup / --clock manual; Pico W: SNTP).
  /// nullptr: no clock, and tracking is refused.
  void attach_utc_clock(const hal::WallClock* clock) { utc_clock_ = clock; }
  /// Target evaluations (SGP4 + look angles) one tick may do for the
  /// tracker's pass search and planning (Pico W: 1, about 3 ms).
  void set_track_budget(int evaluations_per_tick) { tracker_.set_budget(evaluations_per_tick); }
  /// How far the tracking mode's followers lead the target, in bands
  /// (default 0.8; 0 for the plain follower the benchmarks compare with).
  void set_follow_lead(float bands) { tracker_.set_follow_lead(bands); }
  /// The stored TLEs, for recognising what a client's go-to stream follows
  /// (track.recognise), or nullptr (the Sun and the Moon only).
  void attach_catalog(const tracking::TleCatalog* catalog) { catalog_ = catalog; }
  /// The command layer's log (rotator/command_journal.hpp); nullptr: none.
  void attach_journal(CommandJournal* journal) { journal_ = journal; }
  CommandJournal* journal() const { return journal_; }
  /// Candidates (TLE entries, the Sun, the Moon) compared per go-to at most
  /// (rotator/goto_match.hpp says why; Pico W: 3, about 10-30 ms).
  void set_recognise_budget(int candidates_per_goto) {
    recognise_budget_ = candidates_per_goto < 1 ? 1 : candidates_per_goto;
  }

  // Commands. Each validates everything before it changes anything.
  /// A go-to. `source` names who sent it (a session, REST or MQTT from an
  /// address): a stream of go-tos from one source that moves like a tracker
  /// gets the continuity rule (rotator/goto_stream.hpp, track.continuity):
  /// a 0..360 azimuth goes on the turn continuous with the stream, inside
  /// the travel, rather than the literal one. kNoSource: always literal.
  /// A stream recognised as following a stored satellite, the Sun or the
  /// Moon (track.recognise) is followed along that object's planned pass;
  /// its go-tos that stay on the object are then taken as confirmation, and
  /// one that departs from it, or any other command, ends the recognition
  /// and is obeyed literally.
  Error go_to(std::optional<float> az_deg, std::optional<float> el_deg,
              AzTarget az_mode = AzTarget::kCompass, CommandSource source = kNoSource);
  /// Moves one axis until stop, a limit, or for `deadman_ms` (0 = no dead-man;
  /// the web's hold-to-move buttons renew it).
  Error move(AxisId axis, Direction dir, int speed_pct = -1, Millis deadman_ms = 0);
  /// Ends the jog on `axis` if it still jogs, and nothing else (not a
  /// command: a manual button's release, command/buttons.hpp).
  void end_jog(AxisId axis);
  void stop();
  Error park();
  /// Stops, clears latched faults, restores the default speed. kFaulted,
  /// and nothing cleared, while the emergency-stop input is active.
  Error reset();
  Error set_speed_pct(int pct);
  /// Arms the tracking mode (docs/tracking.md): refused without a valid
  /// clock, with bad elements, a latched fault, or ("now") a target below
  /// track.min_el_deg. Any other command, STOP included, ends it.
  TrackError track(const TrackRequest& request);
  const TrackStatus& track_status() const { return tracker_.status(); }
  const Tracker& tracker() const { return tracker_; }
  /// UTC now, when the clock is known and may be trusted for tracking.
  std::optional<std::int64_t> utc_ms() const;
  /// The station (station.* settings) as an observer.
  tracking::Observer observer() const;
  /// Whether the station's position was ever set: 0 N 0 E, the default, is
  /// taken as "not set" (open sea in the Gulf of Guinea), and nothing is
  /// computed for it (TrackError::kNoStation).
  bool station_set() const;

  /// Starts self-commissioning of one axis (docs/commissioning.md) after a
  /// stop; refused (reason in `why`) while tracking, without a sensor or
  /// with a latched fault. STOP and any other command abort it.
  Error commission(const Commissioning::Request& request, const char** why);
  const Commissioning& commissioning() const { return commissioning_; }
  /// Writes the finished run's proposal into the settings (validated as a
  /// whole); the caller saves them as after any settings change.
  settings::Rejection accept_commissioning();

  RotatorStatus status() const;
  Limits limits() const;
  bool has_el() const { return has_el_; }
  /// Whether a speed changes anything: false when every drive is plain
  /// relays (one speed), where the speed setting and commands do nothing.
  bool speed_applies() const {
    return az_.config().drive != DriveType::kRelay ||
           (has_el_ && el_.config().drive != DriveType::kRelay);
  }
  Millis now() const { return now_; }
  settings::Settings& settings() { return settings_; }
  const settings::Settings& settings() const { return settings_; }
  /// The control lock (access/control_lock.hpp): every command source asks
  /// it before a move or a setting change; STOP never does.
  access::ControlLock& control_lock() { return control_lock_; }
  const access::ControlLock& control_lock() const { return control_lock_; }

  /// Faults of `kind` latched on `axis` since the controller started (GET
  /// /metrics: rotord_axis_faults_total, stalls among them).
  std::uint32_t faults_latched(AxisId axis, AxisFault kind) const {
    return faults_latched_[static_cast<std::size_t>(axis_index(axis))]
                          [static_cast<std::size_t>(kind)];
  }

  /// The wear odometer (docs/care.md), counted every tick; the port keeps
  /// it across restarts (care::OdometerSaver) and resets it.
  const care::Odometer& odometer() const { return odometer_; }
  care::Odometer& odometer() { return odometer_; }
  /// The starts-per-hour ceiling's view of `axis` (care.max_starts_h).
  const care::StartCeiling& start_ceiling(AxisId axis) const {
    return ceilings_[static_cast<std::size_t>(axis_index(axis))];
  }
  /// Go-tos the ceiling held at rest since start (each wait counted once).
  std::uint32_t starts_held(AxisId axis) const {
    return starts_held_[static_cast<std::size_t>(axis_index(axis))];
  }

  /// Wind stow (docs/care.md, "Wind stow"; controller_wind.cpp): the rule,
  /// its readings and counts. While it refuses, go-tos, jogs, PARK, tracks
  /// and self-commissioning answer Error::kStowed; STOP always works.
  const care::WindStow& wind() const { return wind_; }
  /// The anemometer's pulse counter (pins.wind / gpiod.wind), or nullptr;
  /// read every tick when wind.source is pulses.
  void attach_wind_pulses(hal::PulseCounter* counter) { wind_pulses_ = counter; }
  /// A message on wind.mqtt_topic (speed in wind.mqtt_unit) or on
  /// wind.mqtt_dir_topic (deg): taken when wind.source uses it, else
  /// ignored; garbage is counted.
  void wind_speed_message(std::string_view payload);
  void wind_direction_message(std::string_view payload);
  /// An operator lifts the stow's refusal for `minutes` (0: wind.override_min);
  /// kNotFound when nothing is stowed. end_wind_override() stows again if
  /// still windy.
  Error wind_override(int minutes);
  void end_wind_override();
  /// The heading a stow goes to now (compass, resolved within the travel).
  float wind_stow_az_deg() const;

  /// What the continuity rule added to the last go-to's azimuth (whole
  /// turns; 0 when it was taken literally). A session that sent it reports
  /// positions in its own frame from then on (rotator/client_frame.hpp).
  float az_continuity_shift_deg() const { return az_shift_deg_; }
  /// Go-tos the continuity rule put on another turn than the literal one
  /// (GET /metrics: rotord_goto_continuity_total).
  std::uint32_t continuity_resolved() const { return stream_.resolved_count(); }
  /// Go-tos of a stream whose axes the lead rule led ahead or held
  /// (rotator/stream_lead.hpp, track.stream_lead; GET /metrics:
  /// rotord_goto_led_total).
  std::uint32_t stream_led() const { return lead_.led_count(); }

  /// What the go-to stream of a client was recognised as following, and when
  /// and why the last recognition ended.
  const Recognition& recognition() const { return recognition_; }
  /// Whether the last go-to obeyed began or continued a recognised pass: the
  /// session that sent it reads the position in its own frame
  /// (rotator/client_frame.hpp).
  bool last_goto_recognised() const { return last_goto_recognised_; }
  /// Where the recognised object is now (azimuth 0..360), while its pass is
  /// followed: a client's frame reads the position on the turn nearest it.
  std::optional<float> recognised_az_deg() const {
    if (!recognition_.active || tracker_.status().phase != TrackPhase::kTracking)
      return std::nullopt;
    return tracker_.status().sky_az_deg;
  }

  /// Resolves a compass azimuth to the literal unwrapped target go_to would
  /// use (without the continuity rule).
  std::optional<float> resolve_az(float az_deg, AzTarget mode) const;

 private:
  void apply_settings();
  /// Any command restarts the idle time park.after_idle_min counts, and
  /// ends a track.
  void note_command();
  /// The lead rule's decision for one axis of a stream's go-to.
  StreamLead::Plan lead_axis(const Axis& axis, float sent_deg,
                             const StreamLead::Axis& stream) const;
  void end_track();
  /// A go-to's axes part: validates and moves, with the continuity rule.
  Error goto_axes(std::optional<float> az_deg, std::optional<float> el_deg, AzTarget az_mode,
                  CommandSource source, GotoStream::Step& step);
  /// Compares an obeyed go-to of a stream with the sky; begins following
  /// the object it recognises.
  void consider_recognition(float az_deg, float el_deg, const GotoStream::Step& step,
                            CommandSource source);
  /// Whether a go-to of the recognised stream stays on the object.
  bool on_recognised(float az_deg, float el_deg);
  void end_recognition(RecognitionEnd why);
  void tick_tracker(Millis now);
  void park_when_idle_long_enough(Millis now);
  void read_estop();
  /// Counts each fault an axis latched since the last call.
  void count_faults();
  /// The odometer and the starts ceiling, after the axes ticked.
  void count_wear(Millis now);
  /// The wind rule's step: its readings, and the stow move when it asks.
  void tick_wind(Millis now);
  care::WindConfig wind_config() const;
  Axis& commissioned_axis() { return commissioning_.axis() == AxisId::kEl ? el_ : az_; }

  settings::Settings& settings_;
  access::ControlLock control_lock_;
  hal::DigitalIn* estop_ = nullptr;
  bool estop_active_ = false;
  Axis az_;
  Axis el_;
  bool has_el_;
  std::uint32_t applied_revision_ = 0;
  Mode mode_ = Mode::kIdle;
  int speed_pct_ = 50;
  Millis now_ = 0;
  Millis last_activity_ms_ = 0;  // last command, or last tick with motion
  bool auto_parked_ = false;     // parked for being idle; no command since
  const hal::WallClock* utc_clock_ = nullptr;
  Tracker tracker_;
  GotoStream stream_;          // the continuity rule's view of the go-tos
  StreamLead lead_;            // the lead rule's view of the same stream
  float az_shift_deg_ = 0.0f;  // what it added to the last go-to
  const tracking::TleCatalog* catalog_ = nullptr;
  CommandJournal* journal_ = nullptr;
  GotoMatcher matcher_;  // what the stream follows; while recognised, holds the object
  int recognise_budget_ = GotoMatcher::kMaxCandidates;
  Recognition recognition_;
  bool last_goto_recognised_ = false;
  Commissioning commissioning_;
  care::Odometer odometer_;
  std::array<care::StartCeiling, kMaxAxes> ceilings_;
  std::array<bool, kMaxAxes> was_held_{};
  std::array<std::uint32_t, kMaxAxes> starts_held_{};
  care::WindStow wind_;
  care::WindPulseMeter wind_meter_;
  bool stow_pending_ = false;  ///< the stow move is to be (re)commanded
  hal::PulseCounter* wind_pulses_ = nullptr;
  std::array<AxisFault, kMaxAxes> counted_fault_{};  // each axis's fault, as last counted
  std::array<std::array<std::uint32_t, kAxisFaultKinds>, kMaxAxes> faults_latched_{};
};

}  // namespace rotord
