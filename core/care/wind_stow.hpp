#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "util/time.hpp"

namespace rotord::care {

/// Where the wind speed comes from (wind.source).
enum class WindSource : std::uint8_t { kOff, kMqtt, kPulses };

/// What the wind rule is doing (docs/care.md, "Wind stow").
enum class WindState : std::uint8_t {
  kOff,       ///< no source configured: nothing judged, nothing refused
  kCalm,      ///< below wind.stow_mps (or no reading yet)
  kRising,    ///< at or above wind.stow_mps, not yet for wind.hold_s
  kStowed,    ///< stowing or stowed: other moves refused until calm
  kOverride,  ///< stowed, but an operator lifted the refusal for a time
};
const char* wind_state_name(WindState s);

/// Why a wind reading was not taken; each counted.
enum class WindReject : std::uint8_t {
  kGarbage,       ///< not a number
  kNegative,      ///< a speed below 0
  kTooHigh,       ///< above kMaxSpeedMps: no anemometer on a rotator's mast reads that
  kBadDirection,  ///< a direction that is not a number in 0..360
  kStale,         ///< no reading for kStaleMs (counted once per silence)
};
constexpr std::size_t kWindRejectKinds = 5;
const char* wind_reject_name(WindReject r);

struct WindConfig {
  WindSource source = WindSource::kOff;
  float stow_mps = 20.0f;
  float calm_mps = 15.0f;
  Millis hold_ms = 10000;
  Millis calm_ms = 600000;
  Millis override_ms = 1800000;
  bool into_wind = false;  ///< aim at the wind's direction, not wind.stow_az_deg
};

/// The wind-stow rule: a wind speed at or above wind.stow_mps for
/// wind.hold_s stows the antenna and refuses other moves until it has read
/// below wind.calm_mps for wind.calm_min; an operator may lift the refusal
/// for wind.override_min. Fixed members only: it runs in the control tick
/// (M0+: no heap, no exceptions).
class WindStow {
 public:
  static constexpr float kMaxSpeedMps = 120.0f;
  /// A source silent this long no longer counts as a reading: the rule
  /// neither stows on nor is calmed by an old value (a stow stays).
  static constexpr Millis kStaleMs = 120000;
  /// Boom into the wind: the stow is aimed again once the wind has veered
  /// this far from where it was aimed (not at every degree of it).
  static constexpr float kReaimDeg = 30.0f;

  void configure(const WindConfig& config);
  const WindConfig& config() const { return config_; }

  /// A speed reading (m/s). Refused ones are counted, never taken.
  void speed(float mps, Millis now);
  /// A direction reading (deg, where the wind comes from, 0..360).
  void direction(float deg, Millis now);
  /// A reading that could not be read at all.
  void reject(WindReject why) { ++rejected_[static_cast<std::size_t>(why)]; }
  /// A text payload (MQTT): a decimal number, optionally in whitespace;
  /// `to_mps` converts its unit.
  void speed_text(std::string_view text, float to_mps, Millis now);
  void direction_text(std::string_view text, Millis now);

  /// Steps the rule. Call every control tick.
  void tick(Millis now);

  /// Lifts the refusal for the configured time (`for_ms` 0: wind.override_min);
  /// false (nothing changed) unless stowed.
  bool override_now(Millis now, Millis for_ms = 0);
  /// Ends an override at once: stowed again if still windy.
  void end_override();

  WindState state() const { return state_; }
  /// Whether other moves are refused now.
  bool refusing() const { return state_ == WindState::kStowed; }
  /// Set when a stow should be (re)commanded; the controller clears it
  /// once it commanded the move (take_stow_request).
  bool take_stow_request() {
    if (!stow_requested_) return false;
    stow_requested_ = false;
    aimed_ = has_fresh_direction(now_);
    aimed_dir_deg_ = dir_deg_;
    return true;
  }
  /// Whether a direction was read within kStaleMs.
  bool has_fresh_direction(Millis now) const { return have_dir_ && now - dir_at_ms_ <= kStaleMs; }
  /// The stow was cut short by STOP: not commanded again this windy spell
  /// (an operator who stops it has a reason), still refusing.
  void stopped_by_operator() { stopped_ = state_ == WindState::kStowed; }
  bool stopped() const { return stopped_; }
  /// RESET: the stow goes on (true) if stowed, STOP's hold lifted.
  bool restow() {
    if (state_ != WindState::kStowed) return false;
    stopped_ = false;
    return true;
  }

  bool has_speed() const { return have_speed_; }
  float speed_mps() const { return speed_mps_; }
  bool has_direction() const { return have_dir_; }
  float direction_deg() const { return dir_deg_; }
  /// When the last stow began (now of that tick), -1 if never.
  Millis stowed_at_ms() const { return stowed_at_ms_; }
  /// Override time left (ms), 0 unless overriding.
  Millis override_left_ms(Millis now) const;
  /// Calm time still to wait before the refusal ends (ms), while stowed.
  Millis calm_left_ms(Millis now) const;
  std::uint32_t stows() const { return stows_; }
  std::uint32_t overrides() const { return overrides_; }
  std::uint32_t readings() const { return readings_; }
  std::uint32_t rejected(WindReject why) const { return rejected_[static_cast<std::size_t>(why)]; }

 private:
  void enter_stowed(Millis now);
  bool fresh(Millis now) const { return have_speed_ && now - speed_at_ms_ <= kStaleMs; }

  WindConfig config_;
  WindState state_ = WindState::kOff;
  bool have_speed_ = false;
  float speed_mps_ = 0.0f;
  Millis speed_at_ms_ = 0;
  bool have_dir_ = false;
  float dir_deg_ = 0.0f;
  Millis dir_at_ms_ = 0;
  Millis above_since_ms_ = -1;  ///< first reading of this spell at or above stow_mps
  Millis calm_since_ms_ = -1;   ///< first reading of this spell below calm_mps
  Millis override_until_ms_ = 0;
  Millis stowed_at_ms_ = -1;
  bool stow_requested_ = false;
  bool aimed_ = false;  ///< the last stow commanded was aimed by a direction
  float aimed_dir_deg_ = 0.0f;
  Millis now_ = 0;
  bool stopped_ = false;
  bool stale_counted_ = false;
  std::uint32_t stows_ = 0;
  std::uint32_t overrides_ = 0;
  std::uint32_t readings_ = 0;
  std::array<std::uint32_t, kWindRejectKinds> rejected_{};
};

}  // namespace rotord::care
