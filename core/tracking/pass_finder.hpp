#pragma once
#include <cstdint>

#include "tracking/observer.hpp"
#include "tracking/sky_target.hpp"

namespace rotord::tracking {

/// One pass of a target above a minimum elevation. Times are Unix ms (UTC).
struct Pass {
  std::int64_t aos_ms = 0;     ///< rises through the minimum elevation
  std::int64_t los_ms = 0;     ///< sets through it
  std::int64_t max_el_ms = 0;  ///< culmination
  double max_el_deg = 0;
  double aos_az_deg = 0;
  double los_az_deg = 0;
  double max_el_az_deg = 0;
  double max_az_rate_deg_s = 0;  ///< largest |d az/dt| seen (at culmination for most passes)
  double max_el_rate_deg_s = 0;  ///< largest |d el/dt| seen
  bool aos_clipped = false;      ///< already up at the start of the window: AOS is the start
  bool los_clipped = false;      ///< still up at its end: LOS is the end
};

/// Finds the passes of a target in a time window, a bounded amount of work per
/// call, so that a microcontroller can spread the search over its main loop
/// without delaying a control tick. Scans at a fixed step (from the orbit's
/// period: about 18 s for the ISS, 5 min for the Sun), then bisects AOS and
/// LOS to 0.1 s and the culmination by golden-section search. A pass shorter
/// than the step can be missed. The maximum elevation rate is searched the
/// same way on each side of the culmination (|el rate| rises from AOS to a
/// peak and falls to zero at culmination); the maximum azimuth rate is the
/// largest seen, the culmination's for an ordinary pass (above about 85 deg
/// its spike is narrower than the 0.1 s the search resolves).
///
///   finder.start(target, observer, from, to, 0.0);
///   for (;;) { status = finder.step(20); if (status == kFound) use(finder.pass()); ... }
class PassFinder {
 public:
  enum class Status : std::uint8_t {
    kSearching,  ///< call step() again
    kFound,      ///< pass() holds the next pass; call step() again for the one after
    kDone,       ///< no more passes in the window
    kError,      ///< the target cannot be computed (error()), e.g. decayed by then
  };

  /// The target is used by reference and must live until the search ends.
  void start(SkyTarget& target, const Observer& observer, std::int64_t from_ms, std::int64_t to_ms,
             double min_el_deg, double scan_step_s = 0.0);

  /// Works through at most `max_evaluations` look-angle computations.
  Status step(int max_evaluations);

  const Pass& pass() const { return pass_; }
  Sgp4Error error() const { return error_; }
  double scan_step_s() const { return static_cast<double>(step_ms_) / 1000.0; }

  /// The scan step start() picks when none is given: 1/300 of the orbital
  /// period within 5..600 s; 300 s for the Sun and the Moon.
  static double default_scan_step_s(const SkyTarget& target);

 private:
  enum class Phase : std::uint8_t {
    kIdle,
    kScan,
    kAos,
    kLos,
    kCulmination,  ///< golden section on the elevation
    kRateBefore,   ///< on |el rate| from AOS to culmination
    kRateAfter,    ///< and from culmination to LOS
    kDone,
    kError
  };

  bool evaluate(std::int64_t t, LookAngles& look);
  void note_in_pass(std::int64_t t, const LookAngles& look);
  void begin_golden(Phase phase, std::int64_t a, std::int64_t b);
  double objective(const LookAngles& look) const;
  void golden_done();
  void open_pass(std::int64_t t, const LookAngles& look, bool clipped);
  void emit();
  void begin_culmination();
  void scan_once();
  void bisect_once();
  void golden_once();

  SkyTarget* target_ = nullptr;
  Observer observer_;
  std::int64_t from_ms_ = 0, to_ms_ = 0, step_ms_ = 0;
  double min_el_deg_ = 0;
  Phase phase_ = Phase::kIdle;
  Status pending_ = Status::kSearching;
  Sgp4Error error_ = Sgp4Error::kOk;

  // Scan state: the last sample.
  std::int64_t t_ = 0;
  std::int64_t prev_t_ = 0;
  LookAngles prev_look_;
  bool have_prev_ = false;
  bool in_pass_ = false;
  // Bisection bracket: lo is on the side of the previous state.
  std::int64_t lo_ = 0, hi_ = 0;
  LookAngles edge_look_;
  // Best sample of the pass so far.
  std::int64_t best_t_ = 0;
  LookAngles best_look_;
  // Golden-section bracket and inner points.
  std::int64_t ga_ = 0, gb_ = 0, gc_ = 0, gd_ = 0;
  double fc_ = 0, fd_ = 0;
  std::uint8_t golden_points_ = 0;  // inner points evaluated so far (0..2)
  Pass pass_;
};

}  // namespace rotord::tracking
