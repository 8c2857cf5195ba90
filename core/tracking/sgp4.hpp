#pragma once
#include <cstdint>

#include "tracking/tle.hpp"

namespace rotord::tracking {

/// SGP4's error codes, numbered as in Vallado et al. (2006), so that they
/// compare one to one with the verification output.
enum class Sgp4Error : std::uint8_t {
  kOk = 0,
  kEccentricity = 1,           ///< mean eccentricity outside [-0.001, 1)
  kMeanMotion = 2,             ///< mean motion not positive
  kPerturbedEccentricity = 3,  ///< perturbed eccentricity outside [0, 1]
  kSemiLatusRectum = 4,        ///< semi-latus rectum negative
  kDecayed = 6,                ///< the orbit is below the Earth's surface
  kNoTarget = 7,               ///< not SGP4's: nothing to propagate (SkyTarget)
};

const char* sgp4_error_name(Sgp4Error error);

/// Position (km) and velocity (km/s) in TEME, the frame SGP4 works in.
struct TemeState {
  double r_km[3] = {};
  double v_km_s[3] = {};
};

/// The deep-space (SDP4) terms: lunar-solar periodics and the resonance
/// integrator for 12 h and 24 h orbits. Kept apart so near-Earth objects can
/// see at a glance which of them they never touch.
struct DeepSpaceTerms {
  // Lunar-solar periodics (dscom/dpper).
  double e3, ee2, peo, pgho, pho, pinco, plo, se2, se3, sgh2, sgh3, sgh4, sh2, sh3, si2, si3, sl2,
      sl3, sl4, xgh2, xgh3, xgh4, xh2, xh3, xi2, xi3, xl2, xl3, xl4, zmol, zmos;
  // Secular rates (dsinit).
  double dedt, didt, dmdt, dnodt, domdt;
  // Resonance (dsinit/dspace): 0 none, 1 one-day, 2 half-day.
  int irez;
  double d2201, d2211, d3210, d3222, d4410, d4422, d5220, d5232, d5421, d5433;
  double del1, del2, del3, xfact, xlamo;
  // Integrator state: the last step reached, so that the next call continues
  // from it instead of from epoch (same steps either way, so same result).
  double atime, xli, xni;
};

/// SGP4/SDP4 as published in Vallado, Crawford, Hujsak and Kelso, "Revisiting
/// Spacetrack Report #3" (AIAA 2006-6753), with WGS-72 constants and the
/// "improved" operation mode (GMST from the IAU-82 formula, the mode of the
/// reference output tcppver.out). Double precision throughout; no heap, no
/// exceptions; about 1 KB per object.
class Sgp4 {
 public:
  /// Converts the elements and computes every constant of the orbit. Returns
  /// the error of the state at epoch (as Vallado's sgp4init does): an object
  /// that fails here cannot be propagated.
  Sgp4Error init(const Tle& tle);

  /// The state `tsince_min` minutes after epoch (negative: before). Not const:
  /// deep-space resonant orbits keep their integrator position between calls.
  Sgp4Error propagate(double tsince_min, TemeState& out);

  /// Epoch as milliseconds since 1970-01-01 UTC (fractional).
  double epoch_unix_ms() const { return epoch_unix_ms_; }
  /// Epoch as days since 1949-12-31 00:00 UTC, SGP4's own time origin.
  double epoch_days_1950() const { return epoch_1950_; }
  /// True for periods of 225 min and more (SDP4's deep-space terms).
  bool deep_space() const { return deep_space_; }
  /// Mean motion, revolutions per day (Kozai, as in the TLE).
  double mean_motion_rev_day() const;

 private:
  // Elements in SGP4 units (radians, radians per minute).
  double epoch_1950_ = 0, epoch_unix_ms_ = 0;
  double bstar_ = 0, ecco_ = 0, argpo_ = 0, inclo_ = 0, mo_ = 0, no_kozai_ = 0, nodeo_ = 0;
  double no_unkozai_ = 0;
  // Near-Earth constants.
  bool simple_ = false;      // perigee below 220 km: drop some drag terms
  bool deep_space_ = false;  // period >= 225 min
  double aycof_ = 0, con41_ = 0, cc1_ = 0, cc4_ = 0, cc5_ = 0, d2_ = 0, d3_ = 0, d4_ = 0;
  double delmo_ = 0, eta_ = 0, argpdot_ = 0, omgcof_ = 0, sinmao_ = 0, t2cof_ = 0, t3cof_ = 0;
  double t4cof_ = 0, t5cof_ = 0, x1mth2_ = 0, x7thm1_ = 0, mdot_ = 0, nodedot_ = 0, xlcof_ = 0;
  double xmcof_ = 0, nodecf_ = 0, gsto_ = 0;
  DeepSpaceTerms ds_{};
};

}  // namespace rotord::tracking
