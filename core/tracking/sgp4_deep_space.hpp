#pragma once
// Internal to sgp4.cpp: the deep-space (SDP4) parts of Vallado et al.'s SGP4,
// named after the routines of the paper (dscom, dpper, dsinit, dspace).
#include "tracking/sgp4.hpp"

namespace rotord::tracking::deep_space {

/// What dscom computes besides the stored lunar-solar terms, for dsinit.
struct Common {
  double sinim, cosim, emsq;
  double s1, s2, s3, s4, s5;
  double ss1, ss2, ss3, ss4, ss5;
  double sz1, sz3, sz11, sz13, sz21, sz23, sz31, sz33;
  double z1, z3, z11, z13, z21, z23, z31, z33;
};

/// Lunar and solar terms at `epoch_1950` + `tc` minutes (dscom).
void common_terms(double epoch_1950, double ep, double argpp, double tc, double inclp, double nodep,
                  double np, DeepSpaceTerms& ds, Common& c);

/// Lunar-solar periodic perturbations at `t` minutes (dpper, after
/// initialisation), improved operation mode.
void periodics(const DeepSpaceTerms& ds, double t, double& ep, double& inclp, double& nodep,
               double& argpp, double& mp);

/// Secular rates and resonance constants (dsinit) at epoch.
struct InitInput {
  double argpo, mo, mdot, no, nodeo, nodedot, xpidot, ecco, eccsq, gsto, inclo;
};
void init_resonance(const InitInput& in, const Common& c, DeepSpaceTerms& ds);

/// Secular effects and the resonance integration to `t` minutes (dspace).
void secular(DeepSpaceTerms& ds, double argpo, double argpdot, double t, double gsto, double no,
             double& em, double& argpm, double& inclm, double& mm, double& nodem, double& nm);

}  // namespace rotord::tracking::deep_space
