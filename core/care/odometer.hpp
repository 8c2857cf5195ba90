#pragma once
#include <array>
#include <cstdint>

#include "axis/axis_status.hpp"
#include "util/axis_id.hpp"
#include "util/time.hpp"

namespace rotord::care {

/// What one axis's motor, brake and relays have been through (docs/care.md,
/// "Wear odometer"): the counts an owner compares with the data sheets'
/// ratings (relay operations, motor duty) to judge the wear of a rotator on
/// a tower nobody watches.
struct AxisWear {
  std::uint32_t starts = 0;            ///< the motor was switched on (a drive begun)
  std::uint32_t reversals = 0;         ///< starts in the other direction than the one before
  std::uint64_t run_ms = 0;            ///< time with the motor driven
  std::uint32_t turned_deg = 0;        ///< whole degrees turned under power and coasting
  std::uint32_t brake_cycles = 0;      ///< brake released (and set again)
  std::uint32_t relay_switchings = 0;  ///< relay closures, every relay of the axis
  /// Faults latched, indexed by AxisFault ([0], kNone, stays 0).
  std::array<std::uint32_t, kAxisFaultKinds> faults{};

  std::uint32_t faults_total() const;
};

/// Counts one axis's wear from its status, once a control tick. Plain
/// members, no heap: it runs inside the tick (Controller::tick). Edges of the
/// drive outputs are counted, not the state machine's words, so what is
/// counted is what the relays and the motor were really given.
class AxisOdometer {
 public:
  /// One tick's status; `now` is the controller's clock.
  void observe(const AxisStatus& s, Millis now);
  const AxisWear& wear() const { return wear_; }
  /// The counts read back from storage (start-up), or zero (a reset).
  void restore(const AxisWear& wear);

 private:
  /// Adds the turn of the drive that ends now.
  void close_segment(const AxisStatus& s);

  AxisWear wear_;
  bool seen_ = false;  ///< a first status was seen (no edges before it)
  DriveOutputs last_out_;
  AxisFault last_fault_ = AxisFault::kNone;
  Direction last_start_dir_ = Direction::kNone;
  Millis last_now_ = 0;
  bool segment_open_ = false;      ///< a drive started at segment_from_deg_ ...
  float segment_from_deg_ = 0.0f;  ///< ... and has not come to rest yet
  float carry_deg_ = 0.0f;         ///< the fraction of a degree not yet counted
};

/// Both axes' odometers, when they were last reset, and a change count the
/// saver watches (odometer_saver.hpp).
class Odometer {
 public:
  void observe(const AxisStatus& az, const AxisStatus& el, Millis now);
  const AxisOdometer& axis(AxisId id) const { return axes_[axis_index(id) == 0 ? 0 : 1]; }
  AxisOdometer& axis(AxisId id) { return axes_[axis_index(id) == 0 ? 0 : 1]; }
  /// Unix seconds of the last reset (0: never reset, or the clock was not
  /// known then).
  std::int64_t reset_unix_s() const { return reset_unix_s_; }
  /// Every count back to zero, dated.
  void reset(std::int64_t unix_s);
  /// The counts and the date read back from storage (start-up): not a
  /// change, so nothing is written back.
  void restore(const AxisWear& az, const AxisWear& el, std::int64_t reset_unix_s);
  /// Moves on whenever any count changes (the saver writes only then).
  std::uint32_t revision() const { return revision_; }
  /// Resets since start: the saver writes a reset at once, so a power cut
  /// cannot bring the old counts back.
  std::uint32_t resets() const { return resets_; }
  void touch() { ++revision_; }

 private:
  std::array<AxisOdometer, kMaxAxes> axes_;
  std::int64_t reset_unix_s_ = 0;
  std::uint32_t revision_ = 0;
  std::uint32_t resets_ = 0;
  std::uint64_t summary_ = 0;  ///< the counts' sum at the last observe (changes bump revision_)
};

}  // namespace rotord::care
