// SDP4's deep-space terms, from Vallado, Crawford, Hujsak and Kelso,
// "Revisiting Spacetrack Report #3" (AIAA 2006-6753), section on dscom, dpper,
// dsinit and dspace. The numeric constants are the paper's; the order of the
// arithmetic follows it closely, because the verification output is matched to
// a millimetre over years of propagation.
#include "tracking/sgp4_deep_space.hpp"

#include <cmath>

#include "tracking/wgs72.hpp"

namespace rotord::tracking::deep_space {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
// Solar and lunar perturbation constants.
constexpr double kZes = 0.01675;
constexpr double kZel = 0.05490;
constexpr double kZns = 1.19459e-5;
constexpr double kZnl = 1.5835218e-4;
// Earth rotation, rad/min.
constexpr double kRptim = 4.37526908801129966e-3;

}  // namespace

void common_terms(double epoch_1950, double ep, double argpp, double tc, double inclp, double nodep,
                  double np, DeepSpaceTerms& ds, Common& c) {
  constexpr double c1ss = 2.9864797e-6;
  constexpr double c1l = 4.7968065e-7;
  constexpr double zsinis = 0.39785416;
  constexpr double zcosis = 0.91744867;
  constexpr double zcosgs = 0.1945905;
  constexpr double zsings = -0.98088458;

  const double nm = np;
  const double em = ep;
  const double snodm = std::sin(nodep);
  const double cnodm = std::cos(nodep);
  const double sinomm = std::sin(argpp);
  const double cosomm = std::cos(argpp);
  c.sinim = std::sin(inclp);
  c.cosim = std::cos(inclp);
  c.emsq = em * em;
  const double betasq = 1.0 - c.emsq;
  const double rtemsq = std::sqrt(betasq);

  ds.peo = 0.0;
  ds.pinco = 0.0;
  ds.plo = 0.0;
  ds.pgho = 0.0;
  ds.pho = 0.0;
  const double day = epoch_1950 + 18261.5 + tc / 1440.0;
  const double xnodce = std::fmod(4.5236020 - 9.2422029e-4 * day, kTwoPi);
  const double stem = std::sin(xnodce);
  const double ctem = std::cos(xnodce);
  const double zcosil = 0.91375164 - 0.03568096 * ctem;
  const double zsinil = std::sqrt(1.0 - zcosil * zcosil);
  const double zsinhl = 0.089683511 * stem / zsinil;
  const double zcoshl = std::sqrt(1.0 - zsinhl * zsinhl);
  const double gam = 5.8351514 + 0.0019443680 * day;
  double zx = 0.39785416 * stem / zsinil;
  const double zy = zcoshl * ctem + 0.91744867 * zsinhl * stem;
  zx = std::atan2(zx, zy);
  zx = gam + zx - xnodce;
  const double zcosgl = std::cos(zx);
  const double zsingl = std::sin(zx);

  // First the Sun's terms (pass 1), then the Moon's (pass 2).
  double zcosg = zcosgs, zsing = zsings, zcosi = zcosis, zsini = zsinis;
  double zcosh = cnodm, zsinh = snodm;
  double cc = c1ss;
  const double xnoi = 1.0 / nm;
  double s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0;
  double z1 = 0, z2 = 0, z3 = 0, z11 = 0, z12 = 0, z13 = 0, z21 = 0, z22 = 0, z23 = 0;
  double z31 = 0, z32 = 0, z33 = 0;
  double ss1 = 0, ss2 = 0, ss3 = 0, ss4 = 0, ss5 = 0, ss6 = 0, ss7 = 0;
  double sz1 = 0, sz2 = 0, sz3 = 0, sz11 = 0, sz12 = 0, sz13 = 0, sz21 = 0, sz22 = 0, sz23 = 0;
  double sz31 = 0, sz32 = 0, sz33 = 0;
  for (int pass = 1; pass <= 2; ++pass) {
    const double a1 = zcosg * zcosh + zsing * zcosi * zsinh;
    const double a3 = -zsing * zcosh + zcosg * zcosi * zsinh;
    const double a7 = -zcosg * zsinh + zsing * zcosi * zcosh;
    const double a8 = zsing * zsini;
    const double a9 = zsing * zsinh + zcosg * zcosi * zcosh;
    const double a10 = zcosg * zsini;
    const double a2 = c.cosim * a7 + c.sinim * a8;
    const double a4 = c.cosim * a9 + c.sinim * a10;
    const double a5 = -c.sinim * a7 + c.cosim * a8;
    const double a6 = -c.sinim * a9 + c.cosim * a10;

    const double x1 = a1 * cosomm + a2 * sinomm;
    const double x2 = a3 * cosomm + a4 * sinomm;
    const double x3 = -a1 * sinomm + a2 * cosomm;
    const double x4 = -a3 * sinomm + a4 * cosomm;
    const double x5 = a5 * sinomm;
    const double x6 = a6 * sinomm;
    const double x7 = a5 * cosomm;
    const double x8 = a6 * cosomm;

    z31 = 12.0 * x1 * x1 - 3.0 * x3 * x3;
    z32 = 24.0 * x1 * x2 - 6.0 * x3 * x4;
    z33 = 12.0 * x2 * x2 - 3.0 * x4 * x4;
    z1 = 3.0 * (a1 * a1 + a2 * a2) + z31 * c.emsq;
    z2 = 6.0 * (a1 * a3 + a2 * a4) + z32 * c.emsq;
    z3 = 3.0 * (a3 * a3 + a4 * a4) + z33 * c.emsq;
    z11 = -6.0 * a1 * a5 + c.emsq * (-24.0 * x1 * x7 - 6.0 * x3 * x5);
    z12 = -6.0 * (a1 * a6 + a3 * a5) +
          c.emsq * (-24.0 * (x2 * x7 + x1 * x8) - 6.0 * (x3 * x6 + x4 * x5));
    z13 = -6.0 * a3 * a6 + c.emsq * (-24.0 * x2 * x8 - 6.0 * x4 * x6);
    z21 = 6.0 * a2 * a5 + c.emsq * (24.0 * x1 * x5 - 6.0 * x3 * x7);
    z22 = 6.0 * (a4 * a5 + a2 * a6) +
          c.emsq * (24.0 * (x2 * x5 + x1 * x6) - 6.0 * (x4 * x7 + x3 * x8));
    z23 = 6.0 * a4 * a6 + c.emsq * (24.0 * x2 * x6 - 6.0 * x4 * x8);
    z1 = z1 + z1 + betasq * z31;
    z2 = z2 + z2 + betasq * z32;
    z3 = z3 + z3 + betasq * z33;
    s3 = cc * xnoi;
    s2 = -0.5 * s3 / rtemsq;
    s4 = s3 * rtemsq;
    s1 = -15.0 * em * s4;
    s5 = x1 * x3 + x2 * x4;
    s6 = x2 * x3 + x1 * x4;
    s7 = x2 * x4 - x1 * x3;

    if (pass == 1) {
      ss1 = s1;
      ss2 = s2;
      ss3 = s3;
      ss4 = s4;
      ss5 = s5;
      ss6 = s6;
      ss7 = s7;
      sz1 = z1;
      sz2 = z2;
      sz3 = z3;
      sz11 = z11;
      sz12 = z12;
      sz13 = z13;
      sz21 = z21;
      sz22 = z22;
      sz23 = z23;
      sz31 = z31;
      sz32 = z32;
      sz33 = z33;
      zcosg = zcosgl;
      zsing = zsingl;
      zcosi = zcosil;
      zsini = zsinil;
      zcosh = zcoshl * cnodm + zsinhl * snodm;
      zsinh = snodm * zcoshl - cnodm * zsinhl;
      cc = c1l;
    }
  }

  ds.zmol = std::fmod(4.7199672 + 0.22997150 * day - gam, kTwoPi);
  ds.zmos = std::fmod(6.2565837 + 0.017201977 * day, kTwoPi);

  // Solar terms.
  ds.se2 = 2.0 * ss1 * ss6;
  ds.se3 = 2.0 * ss1 * ss7;
  ds.si2 = 2.0 * ss2 * sz12;
  ds.si3 = 2.0 * ss2 * (sz13 - sz11);
  ds.sl2 = -2.0 * ss3 * sz2;
  ds.sl3 = -2.0 * ss3 * (sz3 - sz1);
  ds.sl4 = -2.0 * ss3 * (-21.0 - 9.0 * c.emsq) * kZes;
  ds.sgh2 = 2.0 * ss4 * sz32;
  ds.sgh3 = 2.0 * ss4 * (sz33 - sz31);
  ds.sgh4 = -18.0 * ss4 * kZes;
  ds.sh2 = -2.0 * ss2 * sz22;
  ds.sh3 = -2.0 * ss2 * (sz23 - sz21);
  // Lunar terms.
  ds.ee2 = 2.0 * s1 * s6;
  ds.e3 = 2.0 * s1 * s7;
  ds.xi2 = 2.0 * s2 * z12;
  ds.xi3 = 2.0 * s2 * (z13 - z11);
  ds.xl2 = -2.0 * s3 * z2;
  ds.xl3 = -2.0 * s3 * (z3 - z1);
  ds.xl4 = -2.0 * s3 * (-21.0 - 9.0 * c.emsq) * kZel;
  ds.xgh2 = 2.0 * s4 * z32;
  ds.xgh3 = 2.0 * s4 * (z33 - z31);
  ds.xgh4 = -18.0 * s4 * kZel;
  ds.xh2 = -2.0 * s2 * z22;
  ds.xh3 = -2.0 * s2 * (z23 - z21);

  c.s1 = s1;
  c.s2 = s2;
  c.s3 = s3;
  c.s4 = s4;
  c.s5 = s5;
  c.ss1 = ss1;
  c.ss2 = ss2;
  c.ss3 = ss3;
  c.ss4 = ss4;
  c.ss5 = ss5;
  c.sz1 = sz1;
  c.sz3 = sz3;
  c.sz11 = sz11;
  c.sz13 = sz13;
  c.sz21 = sz21;
  c.sz23 = sz23;
  c.sz31 = sz31;
  c.sz33 = sz33;
  c.z1 = z1;
  c.z3 = z3;
  c.z11 = z11;
  c.z13 = z13;
  c.z21 = z21;
  c.z23 = z23;
  c.z31 = z31;
  c.z33 = z33;
}

void periodics(const DeepSpaceTerms& ds, double t, double& ep, double& inclp, double& nodep,
               double& argpp, double& mp) {
  // Solar.
  double zm = ds.zmos + kZns * t;
  double zf = zm + 2.0 * kZes * std::sin(zm);
  double sinzf = std::sin(zf);
  double f2 = 0.5 * sinzf * sinzf - 0.25;
  double f3 = -0.5 * sinzf * std::cos(zf);
  const double ses = ds.se2 * f2 + ds.se3 * f3;
  const double sis = ds.si2 * f2 + ds.si3 * f3;
  const double sls = ds.sl2 * f2 + ds.sl3 * f3 + ds.sl4 * sinzf;
  const double sghs = ds.sgh2 * f2 + ds.sgh3 * f3 + ds.sgh4 * sinzf;
  const double shs = ds.sh2 * f2 + ds.sh3 * f3;
  // Lunar.
  zm = ds.zmol + kZnl * t;
  zf = zm + 2.0 * kZel * std::sin(zm);
  sinzf = std::sin(zf);
  f2 = 0.5 * sinzf * sinzf - 0.25;
  f3 = -0.5 * sinzf * std::cos(zf);
  const double sel = ds.ee2 * f2 + ds.e3 * f3;
  const double sil = ds.xi2 * f2 + ds.xi3 * f3;
  const double sll = ds.xl2 * f2 + ds.xl3 * f3 + ds.xl4 * sinzf;
  const double sghl = ds.xgh2 * f2 + ds.xgh3 * f3 + ds.xgh4 * sinzf;
  const double shll = ds.xh2 * f2 + ds.xh3 * f3;

  const double pe = ses + sel - ds.peo;
  const double pinc = sis + sil - ds.pinco;
  const double pl = sls + sll - ds.plo;
  double pgh = sghs + sghl - ds.pgho;
  double ph = shs + shll - ds.pho;

  inclp = inclp + pinc;
  ep = ep + pe;
  const double sinip = std::sin(inclp);
  const double cosip = std::cos(inclp);
  if (inclp >= 0.2) {
    // Apply the periodics directly.
    ph = ph / sinip;
    pgh = pgh - cosip * ph;
    argpp = argpp + pgh;
    nodep = nodep + ph;
    mp = mp + pl;
  } else {
    // Low inclination: apply them through the Lyddane modification.
    const double sinop = std::sin(nodep);
    const double cosop = std::cos(nodep);
    double alfdp = sinip * sinop;
    double betdp = sinip * cosop;
    const double dalf = ph * cosop + pinc * cosip * sinop;
    const double dbet = -ph * sinop + pinc * cosip * cosop;
    alfdp = alfdp + dalf;
    betdp = betdp + dbet;
    nodep = std::fmod(nodep, kTwoPi);
    double xls = mp + argpp + cosip * nodep;
    const double dls = pl + pgh - pinc * nodep * sinip;
    xls = xls + dls;
    const double xnoh = nodep;
    nodep = std::atan2(alfdp, betdp);
    if (std::fabs(xnoh - nodep) > kPi) {
      if (nodep < xnoh) {
        nodep = nodep + kTwoPi;
      } else {
        nodep = nodep - kTwoPi;
      }
    }
    mp = mp + pl;
    argpp = xls - mp - cosip * nodep;
  }
}

void init_resonance(const InitInput& in, const Common& c, DeepSpaceTerms& ds) {
  constexpr double q22 = 1.7891679e-6;
  constexpr double q31 = 2.1460748e-6;
  constexpr double q33 = 2.2123015e-7;
  constexpr double root22 = 1.7891679e-6;
  constexpr double root44 = 7.3636953e-9;
  constexpr double root54 = 2.1765803e-9;
  constexpr double root32 = 3.7393792e-7;
  constexpr double root52 = 1.1428639e-7;
  const double x2o3 = 2.0 / 3.0;

  const double nm = in.no;
  const double em = in.ecco;
  const double emsq = c.emsq;
  const double cosim = c.cosim;
  const double sinim = c.sinim;

  ds.irez = 0;
  if (nm < 0.0052359877 && nm > 0.0034906585) ds.irez = 1;
  if (nm >= 8.26e-3 && nm <= 9.24e-3 && em >= 0.5) ds.irez = 2;

  // Solar secular terms.
  const double ses = c.ss1 * kZns * c.ss5;
  const double sis = c.ss2 * kZns * (c.sz11 + c.sz13);
  const double sls = -kZns * c.ss3 * (c.sz1 + c.sz3 - 14.0 - 6.0 * emsq);
  const double sghs = c.ss4 * kZns * (c.sz31 + c.sz33 - 6.0);
  double shs = -kZns * c.ss2 * (c.sz21 + c.sz23);
  // Near 0 and 180 deg inclination the node is ill-defined: no node rate.
  const bool polar_node_undefined = in.inclo < 5.2359877e-2 || in.inclo > kPi - 5.2359877e-2;
  if (polar_node_undefined) shs = 0.0;
  if (sinim != 0.0) shs = shs / sinim;
  const double sgs = sghs - cosim * shs;

  // Lunar secular terms.
  ds.dedt = ses + c.s1 * kZnl * c.s5;
  ds.didt = sis + c.s2 * kZnl * (c.z11 + c.z13);
  ds.dmdt = sls - kZnl * c.s3 * (c.z1 + c.z3 - 14.0 - 6.0 * emsq);
  const double sghl = c.s4 * kZnl * (c.z31 + c.z33 - 6.0);
  double shll = -kZnl * c.s2 * (c.z21 + c.z23);
  if (polar_node_undefined) shll = 0.0;
  ds.domdt = sgs + sghl;
  ds.dnodt = shs;
  if (sinim != 0.0) {
    ds.domdt = ds.domdt - cosim / sinim * shll;
    ds.dnodt = ds.dnodt + shll / sinim;
  }

  const double theta = std::fmod(in.gsto, kTwoPi);
  if (ds.irez == 0) return;

  const double aonv = std::pow(nm / wgs72::kXke(), x2o3);
  if (ds.irez == 2) {
    // Half-day resonance (geopotential terms of degree 2..5).
    const double cosisq = cosim * cosim;
    const double e = in.ecco;
    const double esq = in.eccsq;
    const double eoc = e * esq;
    const double g201 = -0.306 - (e - 0.64) * 0.440;
    double g211, g310, g322, g410, g422, g520, g521, g532, g533;
    if (e <= 0.65) {
      g211 = 3.616 - 13.2470 * e + 16.2900 * esq;
      g310 = -19.302 + 117.3900 * e - 228.4190 * esq + 156.5910 * eoc;
      g322 = -18.9068 + 109.7927 * e - 214.6334 * esq + 146.5816 * eoc;
      g410 = -41.122 + 242.6940 * e - 471.0940 * esq + 313.9530 * eoc;
      g422 = -146.407 + 841.8800 * e - 1629.014 * esq + 1083.4350 * eoc;
      g520 = -532.114 + 3017.977 * e - 5740.032 * esq + 3708.2760 * eoc;
    } else {
      g211 = -72.099 + 331.819 * e - 508.738 * esq + 266.724 * eoc;
      g310 = -346.844 + 1582.851 * e - 2415.925 * esq + 1246.113 * eoc;
      g322 = -342.585 + 1554.908 * e - 2366.899 * esq + 1215.972 * eoc;
      g410 = -1052.797 + 4758.686 * e - 7193.992 * esq + 3651.957 * eoc;
      g422 = -3581.690 + 16178.110 * e - 24462.770 * esq + 12422.520 * eoc;
      if (e > 0.715) {
        g520 = -5149.66 + 29936.92 * e - 54087.36 * esq + 31324.56 * eoc;
      } else {
        g520 = 1464.74 - 4664.75 * e + 3763.64 * esq;
      }
    }
    if (e < 0.7) {
      g533 = -919.22770 + 4988.6100 * e - 9064.7700 * esq + 5542.21 * eoc;
      g521 = -822.71072 + 4568.6173 * e - 8491.4146 * esq + 5337.524 * eoc;
      g532 = -853.66600 + 4690.2500 * e - 8624.7700 * esq + 5341.4 * eoc;
    } else {
      g533 = -37995.780 + 161616.52 * e - 229838.20 * esq + 109377.94 * eoc;
      g521 = -51752.104 + 218913.95 * e - 309468.16 * esq + 146349.42 * eoc;
      g532 = -40023.880 + 170470.89 * e - 242699.48 * esq + 115605.82 * eoc;
    }
    const double sini2 = sinim * sinim;
    const double f220 = 0.75 * (1.0 + 2.0 * cosim + cosisq);
    const double f221 = 1.5 * sini2;
    const double f321 = 1.875 * sinim * (1.0 - 2.0 * cosim - 3.0 * cosisq);
    const double f322 = -1.875 * sinim * (1.0 + 2.0 * cosim - 3.0 * cosisq);
    const double f441 = 35.0 * sini2 * f220;
    const double f442 = 39.3750 * sini2 * sini2;
    const double f522 = 9.84375 * sinim *
                        (sini2 * (1.0 - 2.0 * cosim - 5.0 * cosisq) +
                         0.33333333 * (-2.0 + 4.0 * cosim + 6.0 * cosisq));
    const double f523 = sinim * (4.92187512 * sini2 * (-2.0 - 4.0 * cosim + 10.0 * cosisq) +
                                 6.56250012 * (1.0 + 2.0 * cosim - 3.0 * cosisq));
    const double f542 =
        29.53125 * sinim * (2.0 - 8.0 * cosim + cosisq * (-12.0 + 8.0 * cosim + 10.0 * cosisq));
    const double f543 =
        29.53125 * sinim * (-2.0 - 8.0 * cosim + cosisq * (12.0 + 8.0 * cosim - 10.0 * cosisq));
    const double xno2 = nm * nm;
    const double ainv2 = aonv * aonv;
    double temp1 = 3.0 * xno2 * ainv2;
    double temp = temp1 * root22;
    ds.d2201 = temp * f220 * g201;
    ds.d2211 = temp * f221 * g211;
    temp1 = temp1 * aonv;
    temp = temp1 * root32;
    ds.d3210 = temp * f321 * g310;
    ds.d3222 = temp * f322 * g322;
    temp1 = temp1 * aonv;
    temp = 2.0 * temp1 * root44;
    ds.d4410 = temp * f441 * g410;
    ds.d4422 = temp * f442 * g422;
    temp1 = temp1 * aonv;
    temp = temp1 * root52;
    ds.d5220 = temp * f522 * g520;
    ds.d5232 = temp * f523 * g532;
    temp = 2.0 * temp1 * root54;
    ds.d5421 = temp * f542 * g521;
    ds.d5433 = temp * f543 * g533;
    ds.xlamo = std::fmod(in.mo + in.nodeo + in.nodeo - theta - theta, kTwoPi);
    ds.xfact = in.mdot + ds.dmdt + 2.0 * (in.nodedot + ds.dnodt - kRptim) - in.no;
  }
  if (ds.irez == 1) {
    // One-day (synchronous) resonance.
    const double g200 = 1.0 + emsq * (-2.5 + 0.8125 * emsq);
    const double g310 = 1.0 + 2.0 * emsq;
    const double g300 = 1.0 + emsq * (-6.0 + 6.60937 * emsq);
    const double f220 = 0.75 * (1.0 + cosim) * (1.0 + cosim);
    const double f311 = 0.9375 * sinim * sinim * (1.0 + 3.0 * cosim) - 0.75 * (1.0 + cosim);
    double f330 = 1.0 + cosim;
    f330 = 1.875 * f330 * f330 * f330;
    const double del1 = 3.0 * nm * nm * aonv * aonv;
    ds.del2 = 2.0 * del1 * f220 * g200 * q22;
    ds.del3 = 3.0 * del1 * f330 * g300 * q33 * aonv;
    ds.del1 = del1 * f311 * g310 * q31 * aonv;
    ds.xlamo = std::fmod(in.mo + in.nodeo + in.argpo - theta, kTwoPi);
    ds.xfact = in.mdot + in.xpidot - kRptim + ds.dmdt + ds.domdt + ds.dnodt - in.no;
  }
  ds.xli = ds.xlamo;
  ds.xni = in.no;
  ds.atime = 0.0;
}

void secular(DeepSpaceTerms& ds, double argpo, double argpdot, double t, double gsto, double no,
             double& em, double& argpm, double& inclm, double& mm, double& nodem, double& nm) {
  constexpr double fasx2 = 0.13130908;
  constexpr double fasx4 = 2.8843198;
  constexpr double fasx6 = 0.37448087;
  constexpr double g22 = 5.7686396;
  constexpr double g32 = 0.95240898;
  constexpr double g44 = 1.8014998;
  constexpr double g52 = 1.0508330;
  constexpr double g54 = 4.4108898;
  constexpr double stepp = 720.0;
  constexpr double stepn = -720.0;
  constexpr double step2 = 259200.0;

  const double theta = std::fmod(gsto + t * kRptim, kTwoPi);
  em = em + ds.dedt * t;
  inclm = inclm + ds.didt * t;
  argpm = argpm + ds.domdt * t;
  nodem = nodem + ds.dnodt * t;
  mm = mm + ds.dmdt * t;
  if (ds.irez == 0) return;

  // Restart from epoch when the cached step is on the other side of it or
  // beyond the time asked for; the 720 min steps are the same either way.
  if (ds.atime == 0.0 || t * ds.atime <= 0.0 || std::fabs(t) < std::fabs(ds.atime)) {
    ds.atime = 0.0;
    ds.xni = no;
    ds.xli = ds.xlamo;
  }
  const double delt = t > 0.0 ? stepp : stepn;
  double xndt = 0, xldot = 0, xnddt = 0, ft = 0;
  for (;;) {
    if (ds.irez != 2) {
      xndt = ds.del1 * std::sin(ds.xli - fasx2) + ds.del2 * std::sin(2.0 * (ds.xli - fasx4)) +
             ds.del3 * std::sin(3.0 * (ds.xli - fasx6));
      xldot = ds.xni + ds.xfact;
      xnddt = ds.del1 * std::cos(ds.xli - fasx2) +
              2.0 * ds.del2 * std::cos(2.0 * (ds.xli - fasx4)) +
              3.0 * ds.del3 * std::cos(3.0 * (ds.xli - fasx6));
      xnddt = xnddt * xldot;
    } else {
      const double xomi = argpo + argpdot * ds.atime;
      const double x2omi = xomi + xomi;
      const double x2li = ds.xli + ds.xli;
      xndt = ds.d2201 * std::sin(x2omi + ds.xli - g22) + ds.d2211 * std::sin(ds.xli - g22) +
             ds.d3210 * std::sin(xomi + ds.xli - g32) + ds.d3222 * std::sin(-xomi + ds.xli - g32) +
             ds.d4410 * std::sin(x2omi + x2li - g44) + ds.d4422 * std::sin(x2li - g44) +
             ds.d5220 * std::sin(xomi + ds.xli - g52) + ds.d5232 * std::sin(-xomi + ds.xli - g52) +
             ds.d5421 * std::sin(xomi + x2li - g54) + ds.d5433 * std::sin(-xomi + x2li - g54);
      xldot = ds.xni + ds.xfact;
      xnddt =
          ds.d2201 * std::cos(x2omi + ds.xli - g22) + ds.d2211 * std::cos(ds.xli - g22) +
          ds.d3210 * std::cos(xomi + ds.xli - g32) + ds.d3222 * std::cos(-xomi + ds.xli - g32) +
          ds.d5220 * std::cos(xomi + ds.xli - g52) + ds.d5232 * std::cos(-xomi + ds.xli - g52) +
          2.0 * (ds.d4410 * std::cos(x2omi + x2li - g44) + ds.d4422 * std::cos(x2li - g44) +
                 ds.d5421 * std::cos(xomi + x2li - g54) + ds.d5433 * std::cos(-xomi + x2li - g54));
      xnddt = xnddt * xldot;
    }
    if (std::fabs(t - ds.atime) < stepp) {
      ft = t - ds.atime;
      break;
    }
    ds.xli = ds.xli + xldot * delt + xndt * step2;
    ds.xni = ds.xni + xndt * delt + xnddt * step2;
    ds.atime = ds.atime + delt;
  }
  nm = ds.xni + xndt * ft + xnddt * ft * ft * 0.5;
  const double xl = ds.xli + xldot * ft + xndt * ft * ft * 0.5;
  if (ds.irez != 1) {
    mm = xl - 2.0 * nodem + 2.0 * theta;
  } else {
    mm = xl - nodem - argpm + theta;
  }
  const double dndt = nm - no;
  nm = no + dndt;
}

}  // namespace rotord::tracking::deep_space
