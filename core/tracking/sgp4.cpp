// SGP4 from Vallado, Crawford, Hujsak and Kelso, "Revisiting Spacetrack Report
// #3" (AIAA 2006-6753): initialisation (initl, sgp4init) and propagation
// (sgp4), WGS-72, improved operation mode. The paper's variable names are kept
// so that the code can be read against it; the deep-space routines are in
// sgp4_deep_space.cpp.
#include "tracking/sgp4.hpp"

#include <cmath>

#include "tracking/julian.hpp"
#include "tracking/sgp4_deep_space.hpp"
#include "tracking/wgs72.hpp"

namespace rotord::tracking {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kDeg2Rad = kPi / 180.0;
constexpr double kX2o3 = 2.0 / 3.0;
constexpr double kTemp4 = 1.5e-12;  // guard against division by zero at 180 deg inclination
/// Minutes per day over 2 pi: rev/day to rad/min.
constexpr double kXpdotp = 1440.0 / (2.0 * kPi);

}  // namespace

const char* sgp4_error_name(Sgp4Error error) {
  switch (error) {
    case Sgp4Error::kOk:
      return "ok";
    case Sgp4Error::kEccentricity:
      return "mean eccentricity out of range";
    case Sgp4Error::kMeanMotion:
      return "mean motion not positive";
    case Sgp4Error::kPerturbedEccentricity:
      return "perturbed eccentricity out of range";
    case Sgp4Error::kSemiLatusRectum:
      return "semi-latus rectum negative";
    case Sgp4Error::kDecayed:
      return "decayed";
    case Sgp4Error::kNoTarget:
      return "no target";
  }
  return "?";
}

double Sgp4::mean_motion_rev_day() const {
  return no_kozai_ * kXpdotp;
}

Sgp4Error Sgp4::init(const Tle& tle) {
  *this = Sgp4{};
  const double xke = wgs72::kXke();
  const double j2 = wgs72::kJ2;
  const double j3oj2 = wgs72::kJ3 / wgs72::kJ2;
  const double re = wgs72::kRadius_km;

  no_kozai_ = tle.mean_motion_rev_day / kXpdotp;
  bstar_ = tle.bstar;
  ecco_ = tle.eccentricity;
  argpo_ = tle.arg_perigee_deg * kDeg2Rad;
  inclo_ = tle.inclination_deg * kDeg2Rad;
  mo_ = tle.mean_anomaly_deg * kDeg2Rad;
  nodeo_ = tle.raan_deg * kDeg2Rad;
  epoch_unix_ms_ = tle_epoch_unix_ms(tle.epoch_year, tle.epoch_day);
  epoch_1950_ = tle_epoch_days_1950(tle.epoch_year, tle.epoch_day);

  // Atmosphere boundaries of the drag model.
  const double ss = 78.0 / re + 1.0;
  const double qzms2ttemp = (120.0 - 78.0) / re;
  const double qzms2t = qzms2ttemp * qzms2ttemp * qzms2ttemp * qzms2ttemp;

  // initl: recover the original mean motion (un-Kozai) and semi-major axis.
  const double eccsq = ecco_ * ecco_;
  const double omeosq = 1.0 - eccsq;
  const double rteosq = std::sqrt(omeosq);
  const double cosio = std::cos(inclo_);
  const double cosio2 = cosio * cosio;
  const double ak = std::pow(xke / no_kozai_, kX2o3);
  const double d1 = 0.75 * j2 * (3.0 * cosio2 - 1.0) / (rteosq * omeosq);
  double del = d1 / (ak * ak);
  const double adel = ak * (1.0 - del * del - del * (1.0 / 3.0 + 134.0 * del * del / 81.0));
  del = d1 / (adel * adel);
  no_unkozai_ = no_kozai_ / (1.0 + del);
  const double ao = std::pow(xke / no_unkozai_, kX2o3);
  const double sinio = std::sin(inclo_);
  const double po = ao * omeosq;
  const double con42 = 1.0 - 5.0 * cosio2;
  con41_ = -con42 - cosio2 - cosio2;
  const double posq = po * po;
  const double rp = ao * (1.0 - ecco_);
  gsto_ = gmst_rad(epoch_1950_ + 2433281.5 - kJulianDateJ2000);

  // sgp4init proper. (The paper's guard "omeosq >= 0 || no >= 0" holds for
  // every parsed TLE: eccentricity < 1 and mean motion > 0.)
  simple_ = rp < (220.0 / re + 1.0);
  double sfour = ss;
  double qzms24 = qzms2t;
  const double perige = (rp - 1.0) * re;
  // Perigee below 156 km: the drag model's s and qoms2t change.
  if (perige < 156.0) {
    sfour = perige - 78.0;
    if (perige < 98.0) sfour = 20.0;
    const double qzms24temp = (120.0 - sfour) / re;
    qzms24 = qzms24temp * qzms24temp * qzms24temp * qzms24temp;
    sfour = sfour / re + 1.0;
  }
  const double pinvsq = 1.0 / posq;
  const double tsi = 1.0 / (ao - sfour);
  eta_ = ao * ecco_ * tsi;
  const double etasq = eta_ * eta_;
  const double eeta = ecco_ * eta_;
  const double psisq = std::fabs(1.0 - etasq);
  const double coef = qzms24 * std::pow(tsi, 4.0);
  const double coef1 = coef / std::pow(psisq, 3.5);
  const double cc2 = coef1 * no_unkozai_ *
                     (ao * (1.0 + 1.5 * etasq + eeta * (4.0 + etasq)) +
                      0.375 * j2 * tsi / psisq * con41_ * (8.0 + 3.0 * etasq * (8.0 + etasq)));
  cc1_ = bstar_ * cc2;
  double cc3 = 0.0;
  if (ecco_ > 1.0e-4) cc3 = -2.0 * coef * tsi * j3oj2 * no_unkozai_ * sinio / ecco_;
  x1mth2_ = 1.0 - cosio2;
  cc4_ = 2.0 * no_unkozai_ * coef1 * ao * omeosq *
         (eta_ * (2.0 + 0.5 * etasq) + ecco_ * (0.5 + 2.0 * etasq) -
          j2 * tsi / (ao * psisq) *
              (-3.0 * con41_ * (1.0 - 2.0 * eeta + etasq * (1.5 - 0.5 * eeta)) +
               0.75 * x1mth2_ * (2.0 * etasq - eeta * (1.0 + etasq)) * std::cos(2.0 * argpo_)));
  cc5_ = 2.0 * coef1 * ao * omeosq * (1.0 + 2.75 * (etasq + eeta) + eeta * etasq);
  const double cosio4 = cosio2 * cosio2;
  const double temp1 = 1.5 * j2 * pinvsq * no_unkozai_;
  const double temp2 = 0.5 * temp1 * j2 * pinvsq;
  const double temp3 = -0.46875 * wgs72::kJ4 * pinvsq * pinvsq * no_unkozai_;
  mdot_ = no_unkozai_ + 0.5 * temp1 * rteosq * con41_ +
          0.0625 * temp2 * rteosq * (13.0 - 78.0 * cosio2 + 137.0 * cosio4);
  argpdot_ = -0.5 * temp1 * con42 + 0.0625 * temp2 * (7.0 - 114.0 * cosio2 + 395.0 * cosio4) +
             temp3 * (3.0 - 36.0 * cosio2 + 49.0 * cosio4);
  const double xhdot1 = -temp1 * cosio;
  nodedot_ =
      xhdot1 + (0.5 * temp2 * (4.0 - 19.0 * cosio2) + 2.0 * temp3 * (3.0 - 7.0 * cosio2)) * cosio;
  const double xpidot = argpdot_ + nodedot_;
  omgcof_ = bstar_ * cc3 * std::cos(argpo_);
  xmcof_ = 0.0;
  if (ecco_ > 1.0e-4) xmcof_ = -kX2o3 * coef * bstar_ / eeta;
  nodecf_ = 3.5 * omeosq * xhdot1 * cc1_;
  t2cof_ = 1.5 * cc1_;
  if (std::fabs(cosio + 1.0) > 1.5e-12) {
    xlcof_ = -0.25 * j3oj2 * sinio * (3.0 + 5.0 * cosio) / (1.0 + cosio);
  } else {
    xlcof_ = -0.25 * j3oj2 * sinio * (3.0 + 5.0 * cosio) / kTemp4;
  }
  aycof_ = -0.5 * j3oj2 * sinio;
  const double delmotemp = 1.0 + eta_ * std::cos(mo_);
  delmo_ = delmotemp * delmotemp * delmotemp;
  sinmao_ = std::sin(mo_);
  x7thm1_ = 7.0 * cosio2 - 1.0;

  // Periods of 225 minutes and more: deep space (SDP4).
  if ((2.0 * kPi / no_unkozai_) >= 225.0) {
    deep_space_ = true;
    simple_ = true;
    deep_space::Common c{};
    deep_space::common_terms(epoch_1950_, ecco_, argpo_, 0.0, inclo_, nodeo_, no_unkozai_, ds_, c);
    // (The paper calls dpper here with init = 'y', which changes nothing.)
    const deep_space::InitInput in{argpo_, mo_,   mdot_, no_unkozai_, nodeo_, nodedot_,
                                   xpidot, ecco_, eccsq, gsto_,       inclo_};
    deep_space::init_resonance(in, c, ds_);
  }

  if (!simple_) {
    const double cc1sq = cc1_ * cc1_;
    d2_ = 4.0 * ao * tsi * cc1sq;
    const double temp = d2_ * tsi * cc1_ / 3.0;
    d3_ = (17.0 * ao + sfour) * temp;
    d4_ = 0.5 * temp * ao * tsi * (221.0 * ao + 31.0 * sfour) * cc1_;
    t3cof_ = d2_ + 2.0 * cc1sq;
    t4cof_ = 0.25 * (3.0 * d3_ + cc1_ * (12.0 * d2_ + 10.0 * cc1sq));
    t5cof_ = 0.2 *
             (3.0 * d4_ + 12.0 * cc1_ * d3_ + 6.0 * d2_ * d2_ + 15.0 * cc1sq * (2.0 * d2_ + cc1sq));
  }

  TemeState at_epoch;
  return propagate(0.0, at_epoch);
}

Sgp4Error Sgp4::propagate(double tsince_min, TemeState& out) {
  const double t = tsince_min;
  const double xke = wgs72::kXke();
  const double j2 = wgs72::kJ2;
  const double j3oj2 = wgs72::kJ3 / wgs72::kJ2;
  const double re = wgs72::kRadius_km;
  const double vkmpersec = re * xke / 60.0;

  // Secular gravity and atmospheric drag.
  const double xmdf = mo_ + mdot_ * t;
  const double argpdf = argpo_ + argpdot_ * t;
  const double nodedf = nodeo_ + nodedot_ * t;
  double argpm = argpdf;
  double mm = xmdf;
  const double t2 = t * t;
  double nodem = nodedf + nodecf_ * t2;
  double tempa = 1.0 - cc1_ * t;
  double tempe = bstar_ * cc4_ * t;
  double templ = t2cof_ * t2;
  if (!simple_) {
    const double delomg = omgcof_ * t;
    const double delmtemp = 1.0 + eta_ * std::cos(xmdf);
    const double delm = xmcof_ * (delmtemp * delmtemp * delmtemp - delmo_);
    const double temp = delomg + delm;
    mm = xmdf + temp;
    argpm = argpdf - temp;
    const double t3 = t2 * t;
    const double t4 = t3 * t;
    tempa = tempa - d2_ * t2 - d3_ * t3 - d4_ * t4;
    tempe = tempe + bstar_ * cc5_ * (std::sin(mm) - sinmao_);
    templ = templ + t3cof_ * t3 + t4 * (t4cof_ + t * t5cof_);
  }
  double nm = no_unkozai_;
  double em = ecco_;
  double inclm = inclo_;
  if (deep_space_)
    deep_space::secular(ds_, argpo_, argpdot_, t, gsto_, no_unkozai_, em, argpm, inclm, mm, nodem,
                        nm);

  if (nm <= 0.0) return Sgp4Error::kMeanMotion;
  const double am = std::pow(xke / nm, kX2o3) * tempa * tempa;
  nm = xke / std::pow(am, 1.5);
  em = em - tempe;
  if (em >= 1.0 || em < -0.001) return Sgp4Error::kEccentricity;
  if (em < 1.0e-6) em = 1.0e-6;
  mm = mm + no_unkozai_ * templ;
  double xlm = mm + argpm + nodem;
  nodem = std::fmod(nodem, kTwoPi);
  argpm = std::fmod(argpm, kTwoPi);
  xlm = std::fmod(xlm, kTwoPi);
  mm = std::fmod(xlm - argpm - nodem, kTwoPi);

  // Lunar-solar periodics (deep space only).
  double ep = em;
  double xincp = inclm;
  double argpp = argpm;
  double nodep = nodem;
  double mp = mm;
  double sinip = std::sin(inclm);
  double cosip = std::cos(inclm);
  double aycof = aycof_, xlcof = xlcof_, con41 = con41_, x1mth2 = x1mth2_, x7thm1 = x7thm1_;
  if (deep_space_) {
    deep_space::periodics(ds_, t, ep, xincp, nodep, argpp, mp);
    if (xincp < 0.0) {
      xincp = -xincp;
      nodep = nodep + kPi;
      argpp = argpp - kPi;
    }
    if (ep < 0.0 || ep > 1.0) return Sgp4Error::kPerturbedEccentricity;
    sinip = std::sin(xincp);
    cosip = std::cos(xincp);
    aycof = -0.5 * j3oj2 * sinip;
    if (std::fabs(cosip + 1.0) > 1.5e-12) {
      xlcof = -0.25 * j3oj2 * sinip * (3.0 + 5.0 * cosip) / (1.0 + cosip);
    } else {
      xlcof = -0.25 * j3oj2 * sinip * (3.0 + 5.0 * cosip) / kTemp4;
    }
  }

  // Long-period periodics.
  const double axnl = ep * std::cos(argpp);
  double temp = 1.0 / (am * (1.0 - ep * ep));
  const double aynl = ep * std::sin(argpp) + temp * aycof;
  const double xl = mp + argpp + nodep + temp * xlcof * axnl;

  // Kepler's equation, at most 10 Newton steps of at most 0.95 rad.
  const double u = std::fmod(xl - nodep, kTwoPi);
  double eo1 = u;
  double tem5 = 9999.9;
  double sineo1 = 0.0, coseo1 = 0.0;
  for (int ktr = 1; std::fabs(tem5) >= 1.0e-12 && ktr <= 10; ++ktr) {
    sineo1 = std::sin(eo1);
    coseo1 = std::cos(eo1);
    tem5 = 1.0 - coseo1 * axnl - sineo1 * aynl;
    tem5 = (u - aynl * coseo1 + axnl * sineo1 - eo1) / tem5;
    if (std::fabs(tem5) >= 0.95) tem5 = tem5 > 0.0 ? 0.95 : -0.95;
    eo1 = eo1 + tem5;
  }

  // Short-period periodics.
  const double ecose = axnl * coseo1 + aynl * sineo1;
  const double esine = axnl * sineo1 - aynl * coseo1;
  const double el2 = axnl * axnl + aynl * aynl;
  const double pl = am * (1.0 - el2);
  if (pl < 0.0) return Sgp4Error::kSemiLatusRectum;
  const double rl = am * (1.0 - ecose);
  const double rdotl = std::sqrt(am) * esine / rl;
  const double rvdotl = std::sqrt(pl) / rl;
  const double betal = std::sqrt(1.0 - el2);
  temp = esine / (1.0 + betal);
  const double sinu = am / rl * (sineo1 - aynl - axnl * temp);
  const double cosu = am / rl * (coseo1 - axnl + aynl * temp);
  double su = std::atan2(sinu, cosu);
  const double sin2u = (cosu + cosu) * sinu;
  const double cos2u = 1.0 - 2.0 * sinu * sinu;
  temp = 1.0 / pl;
  const double temp1 = 0.5 * j2 * temp;
  const double temp2 = temp1 * temp;
  if (deep_space_) {
    const double cosisq = cosip * cosip;
    con41 = 3.0 * cosisq - 1.0;
    x1mth2 = 1.0 - cosisq;
    x7thm1 = 7.0 * cosisq - 1.0;
  }
  const double mrt = rl * (1.0 - 1.5 * temp2 * betal * con41) + 0.5 * temp1 * x1mth2 * cos2u;
  su = su - 0.25 * temp2 * x7thm1 * sin2u;
  const double xnode = nodep + 1.5 * temp2 * cosip * sin2u;
  const double xinc = xincp + 1.5 * temp2 * cosip * sinip * cos2u;
  const double mvt = rdotl - nm * temp1 * x1mth2 * sin2u / xke;
  const double rvdot = rvdotl + nm * temp1 * (x1mth2 * cos2u + 1.5 * con41) / xke;

  // Orientation vectors, then position and velocity.
  const double sinsu = std::sin(su);
  const double cossu = std::cos(su);
  const double snod = std::sin(xnode);
  const double cnod = std::cos(xnode);
  const double sini = std::sin(xinc);
  const double cosi = std::cos(xinc);
  const double xmx = -snod * cosi;
  const double xmy = cnod * cosi;
  const double ux = xmx * sinsu + cnod * cossu;
  const double uy = xmy * sinsu + snod * cossu;
  const double uz = sini * sinsu;
  const double vx = xmx * cossu - cnod * sinsu;
  const double vy = xmy * cossu - snod * sinsu;
  const double vz = sini * cossu;
  out.r_km[0] = (mrt * ux) * re;
  out.r_km[1] = (mrt * uy) * re;
  out.r_km[2] = (mrt * uz) * re;
  out.v_km_s[0] = (mvt * ux + rvdot * vx) * vkmpersec;
  out.v_km_s[1] = (mvt * uy + rvdot * vy) * vkmpersec;
  out.v_km_s[2] = (mvt * uz + rvdot * vz) * vkmpersec;
  // Below the surface: decayed (the state is still written, as the paper does).
  if (mrt < 1.0) return Sgp4Error::kDecayed;
  return Sgp4Error::kOk;
}

}  // namespace rotord::tracking
