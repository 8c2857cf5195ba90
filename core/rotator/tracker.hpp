#pragma once
#include <cstdint>

#include "axis/axis.hpp"
#include "rotator/axis_follower.hpp"
#include "settings/settings.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/sky_target.hpp"
#include "tracking/track_plan.hpp"

namespace rotord {

/// Where a track stands (docs/tracking.md, "The tracking mode").
enum class TrackPhase : std::uint8_t {
  kOff,             ///< no track; nothing armed
  kFinding,         ///< looking for the pass (a few evaluations per tick)
  kPlanning,        ///< sampling the whole pass to choose wrap and flip
  kWaiting,         ///< planned; waits to pre-position in time for AOS
  kPrepositioning,  ///< moving to where the pass begins
  kTracking,        ///< following the target (AOS..LOS)
  kHolding,         ///< a fixed az/el, held until a command ends it
  kDone,            ///< the pass ended (LOS); after-LOS action taken
  kFailed,          ///< ended by an error (error() says which)
};
const char* track_phase_name(TrackPhase phase);

enum class TrackWhen : std::uint8_t {
  kNow,       ///< the target must be up now; the rest of this pass
  kNextPass,  ///< the pass in progress, else the next one (within 48 h)
};

/// Why a track was refused or ended early.
enum class TrackError : std::uint8_t {
  kOk,
  kNoClock,        ///< no UTC at all (Pico W: SNTP has not answered)
  kClockUnsynced,  ///< Linux: the kernel says the clock is not synchronized
  kBadElements,    ///< SGP4 refuses the elements (sgp4_error() says why)
  kPropagation,    ///< SGP4 failed during the pass (e.g. decayed by then)
  kBelowHorizon,   ///< "now", but the target is below track.min_el_deg
  kNoPass,         ///< no pass above track.min_el_deg within 48 h
  kOutOfRange,     ///< a fixed az/el outside the travel
  kNotSupported,   ///< an elevation on an azimuth-only rotator
  kFaulted,        ///< an axis has (or latched) a fault
  kNoTarget,       ///< nothing to track
  kNoStation,      ///< station.lat_deg / lon_deg never set (both 0)
  kStowed,         ///< the wind stow refuses moves until calm (docs/care.md)
};
const char* track_error_text(TrackError error);

struct TrackRequest {
  tracking::TargetKind kind = tracking::TargetKind::kNone;  ///< kNone: fixed az/el
  tracking::Tle tle;                                        ///< kSatellite
  float az_deg = 0.0f;                                      ///< fixed: compass azimuth
  float el_deg = 0.0f;                                      ///< fixed: elevation
  TrackWhen when = TrackWhen::kNextPass;
};

/// What GET /api/track and the Track page show.
struct TrackStatus {
  TrackPhase phase = TrackPhase::kOff;
  TrackError error = TrackError::kOk;
  tracking::Sgp4Error sgp4_error = tracking::Sgp4Error::kOk;
  tracking::TargetKind kind = tracking::TargetKind::kNone;
  char name[25] = {};
  std::uint32_t catalog = 0;
  bool have_pass = false;
  tracking::Pass pass;
  bool planned = false;
  tracking::PassPlan plan;
  std::int64_t preposition_at_ms = 0;  ///< UTC when the pre-positioning starts
  bool have_target = false;
  float target_az_deg = 0.0f;  ///< where the antenna is asked to point now (its frame)
  float target_el_deg = 0.0f;
  float sky_az_deg = 0.0f;  ///< where the target is now (0..360, above the horizon)
  float sky_el_deg = 0.0f;
  float lag_ms[2] = {0.0f, 0.0f};       ///< measured: command to motion, az and el
  float speed_deg_s[2] = {0.0f, 0.0f};  ///< measured slew speed, az and el
  std::uint32_t unwinds = 0;            ///< turns the follow phase had to take (fits == false)
  bool armed() const {
    return phase != TrackPhase::kOff && phase != TrackPhase::kDone && phase != TrackPhase::kFailed;
  }
};

/// The tracking mode: finds the pass, plans it whole (tracking/track_plan.hpp),
/// pre-positions for AOS and follows. Owned by the Controller, which calls
/// tick() every control tick; a tick does at most `budget` evaluations of the
/// target (SGP4 plus look angles, ~3 ms each on the Pico W), so pass search
/// and planning spread over many ticks; following only interpolates the
/// planned table. No heap.
class Tracker {
 public:
  /// What tick() asks its owner to do when a pass ends.
  enum class Action : std::uint8_t { kNone, kPark, kReturn, kFailed };

  /// Validates and arms a track. `utc_ms` must be a valid UTC (the owner
  /// checks the clock); `az`/`el` are the axes as they are now.
  TrackError start(const TrackRequest& request, std::int64_t utc_ms,
                   const tracking::Observer& observer, const settings::Settings& values, Axis& az,
                   Axis* el);
  /// Ends the track (any command, STOP, a fault); the axes are left to the caller.
  void cancel();
  Action tick(Millis now, std::int64_t utc_ms, Axis& az, Axis* el);

  void set_budget(int evaluations_per_tick) {
    budget_ = evaluations_per_tick < 1 ? 1 : evaluations_per_tick;
  }
  /// The followers' lead in bands (axis_follower.hpp, AxisFollow::lead_bands).
  void set_follow_lead(float bands) {
    for (AxisFollow& f : follow_) f.lead_bands = bands < 0.0f ? 0.0f : bands;
  }
  const TrackStatus& status() const { return status_; }
  bool armed() const { return status_.armed(); }
  /// Where the antenna was when the track began (track.after_los = return).
  float return_az_deg() const { return return_az_deg_; }
  float return_el_deg() const { return return_el_deg_; }
  const tracking::PassTable& table() const { return table_; }

 private:
  void fail(TrackError error, tracking::Sgp4Error sgp4 = tracking::Sgp4Error::kOk);
  void find(std::int64_t utc_ms);
  void plan(std::int64_t utc_ms, Axis& az, Axis* el);
  void position_now(std::int64_t utc_ms, float& az, float& el) const;
  /// Keeps a planned azimuth inside the travel (only a plan that does not
  /// fit needs it: that is the one unwind).
  float inside_az(float az_deg, const Axis& axis);

  TrackStatus status_;
  tracking::SkyTarget target_;
  tracking::Observer observer_;
  tracking::PassFinder finder_;
  tracking::PassTable table_;
  TrackWhen when_ = TrackWhen::kNextPass;
  int after_los_ = 0;  // track.after_los
  float min_el_deg_ = 0.0f;
  int budget_ = 8;
  float return_az_deg_ = 0.0f;
  float return_el_deg_ = 0.0f;
  AxisFollow follow_[2];
  float az_shift_deg_ = 0.0f;         // whole turns added by unwinds
  bool planned_unwind_done_ = false;  // the plan's one unwind has begun
};

}  // namespace rotord
