// Sun and Moon from J. Meeus, "Astronomical Algorithms", 2nd ed.
// (Willmann-Bell 1998): chapter 22 (nutation, short series), 25 and appendix
// III (the Sun from a truncated VSOP87: the low-accuracy formula of chapter 25
// is off by up to 0.01 deg, half the tolerance) and 47 (Moon). Coefficient
// tables are the book's; integers and floats keep them small in flash.
#include "tracking/sun_moon.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "tracking/julian.hpp"

namespace rotord::tracking {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kAu_km = 149597870.7;

double rad(double deg) {
  return std::fmod(deg, 360.0) * kDeg;
}

/// Nutation in longitude and obliquity (radians), and the true obliquity.
struct Nutation {
  double dpsi, deps, eps;
};

Nutation nutation(double t) {
  const double omega = rad(125.04452 - 1934.136261 * t);
  const double l_sun = rad(280.4665 + 36000.7698 * t);
  const double l_moon = rad(218.3165 + 481267.8813 * t);
  const double arcsec = kDeg / 3600.0;
  Nutation n;
  n.dpsi = (-17.20 * std::sin(omega) - 1.32 * std::sin(2 * l_sun) - 0.23 * std::sin(2 * l_moon) +
            0.21 * std::sin(2 * omega)) *
           arcsec;
  n.deps = (9.20 * std::cos(omega) + 0.57 * std::cos(2 * l_sun) + 0.10 * std::cos(2 * l_moon) -
            0.09 * std::cos(2 * omega)) *
           arcsec;
  const double eps0 = (23.0 + 26.0 / 60.0 + 21.448 / 3600.0) * kDeg +
                      (-46.8150 * t - 0.00059 * t * t + 0.001813 * t * t * t) * arcsec;
  n.eps = eps0 + n.deps;
  return n;
}

void spherical_to_vector(double lon, double lat, double eps, double dist_km, double r[3]) {
  // Ecliptic of date to equator of date: rotate about x by the obliquity.
  const double x = std::cos(lat) * std::cos(lon);
  const double y = std::cos(lat) * std::sin(lon);
  const double z = std::sin(lat);
  r[0] = dist_km * x;
  r[1] = dist_km * (y * std::cos(eps) - z * std::sin(eps));
  r[2] = dist_km * (y * std::sin(eps) + z * std::cos(eps));
}

/// A periodic term of VSOP87's Earth series: A cos(B + C tau), A in 1e-8 rad
/// (1e-8 AU for the radius), tau in Julian millennia from J2000 (TT).
struct VsopTerm {
  std::int32_t a;
  float b;
  double c;
};
// Meeus, Appendix III (Earth, truncated VSOP87D): every L0 term; L1, L2, L3
// down to the size that stays below 0.0001 deg within a few centuries of J2000;
// the radius to 1e-6 AU (it only scales the Sun's 8.8" parallax and aberration).
constexpr VsopTerm kL0[] = {
    {175347046, 0.0f, 0.0},       {3341656, 4.6692568f, 6283.07585},
    {34894, 4.6261f, 12566.1517}, {3497, 2.7441f, 5753.3849},
    {3418, 2.8289f, 3.5231},      {3136, 3.6277f, 77713.7715},
    {2676, 4.4181f, 7860.4194},   {2343, 6.1352f, 3930.2097},
    {1324, 0.7425f, 11506.7698},  {1273, 2.0371f, 529.6910},
    {1199, 1.1096f, 1577.3435},   {990, 5.233f, 5884.927},
    {902, 2.045f, 26.298},        {857, 3.508f, 398.149},
    {780, 1.179f, 5223.694},      {753, 2.533f, 5507.553},
    {505, 4.583f, 18849.228},     {492, 4.205f, 775.523},
    {357, 2.920f, 0.067},         {317, 5.849f, 11790.629},
    {284, 1.899f, 796.298},       {271, 0.315f, 10977.079},
    {243, 0.345f, 5486.778},      {206, 4.806f, 2544.314},
    {205, 1.869f, 5573.143},      {202, 2.458f, 6069.777},
    {156, 0.833f, 213.299},       {132, 3.411f, 2942.463},
    {126, 1.083f, 20.775},        {115, 0.645f, 0.980},
    {103, 0.636f, 4694.003},      {102, 0.976f, 15720.839},
    {102, 4.267f, 7.114},         {99, 6.21f, 2146.17},
    {98, 0.68f, 155.42},          {86, 5.98f, 161000.69},
    {85, 1.30f, 6275.96},         {85, 3.67f, 71430.70},
    {80, 1.81f, 17260.15},        {79, 3.04f, 12036.46},
    {71, 1.76f, 5088.63},         {74, 3.50f, 3154.69},
    {74, 4.68f, 801.82},          {70, 0.83f, 9437.76},
    {62, 3.98f, 8827.39},         {61, 1.82f, 7084.90},
    {57, 2.78f, 6286.60},         {56, 4.39f, 14143.50},
    {56, 3.47f, 6279.55},         {52, 0.19f, 12139.55},
    {52, 1.33f, 1748.02},         {51, 0.28f, 5856.48},
    {49, 0.49f, 1194.45},         {41, 5.37f, 8429.24},
    {41, 2.40f, 19651.05},        {39, 6.17f, 10447.39},
    {37, 6.04f, 10213.29},        {37, 2.57f, 1059.38},
    {36, 1.71f, 2352.87},         {36, 1.78f, 6812.77},
    {33, 0.59f, 17789.85},        {30, 0.44f, 83996.85},
    {30, 2.74f, 1349.87},         {25, 3.16f, 4690.48},
};
/// L1's constant term, the Earth's mean motion: 628331966747e-8 rad/millennium.
constexpr double kL1Constant = 628331966747.0;
constexpr VsopTerm kL1[] = {
    {206059, 2.678235f, 6283.07585},
    {4303, 2.6351f, 12566.1517},
    {425, 1.590f, 3.523},
    {119, 5.796f, 26.298},
    {109, 2.966f, 1577.344},
    {93, 2.59f, 18849.23},
    {72, 1.14f, 529.69},
    {68, 1.87f, 398.15},
    {67, 4.41f, 5507.55},
    {59, 2.89f, 5223.69},
    {56, 2.17f, 155.42},
    {45, 0.40f, 796.30},
};
constexpr VsopTerm kL2[] = {
    {52919, 0.0f, 0.0},
    {8720, 1.0721f, 6283.0758},
    {309, 0.867f, 12566.152},
};
constexpr VsopTerm kL3[] = {{289, 5.844f, 6283.076}, {35, 0.0f, 0.0}};
constexpr VsopTerm kR0[] = {
    {100013989, 0.0f, 0.0},      {1670700, 3.0984635f, 6283.07585}, {13956, 3.05525f, 12566.1517},
    {3084, 5.1985f, 77713.7715}, {1628, 1.1739f, 5753.3849},        {1576, 2.8469f, 7860.4194},
};
constexpr VsopTerm kR1[] = {{103019, 1.10749f, 6283.07585}, {1721, 1.0644f, 12566.1517}};

template <std::size_t N>
double vsop_sum(const VsopTerm (&terms)[N], double tau) {
  double sum = 0.0;
  for (const VsopTerm& k : terms) sum += k.a * std::cos(static_cast<double>(k.b) + k.c * tau);
  return sum;
}

void sun_position(double t, const Nutation& n, double r[3]) {
  const double tau = t / 10.0;
  // Earth's heliocentric longitude and distance, then the Sun seen from the Earth.
  const double l =
      (vsop_sum(kL0, tau) + tau * (kL1Constant + vsop_sum(kL1, tau) +
                                   tau * (vsop_sum(kL2, tau) + tau * vsop_sum(kL3, tau)))) *
      1e-8;
  const double r_au = (vsop_sum(kR0, tau) + tau * vsop_sum(kR1, tau)) * 1e-8;
  const double arcsec = kDeg / 3600.0;
  // + 180 deg to geocentric, FK5 correction, nutation, aberration (-20.4898" / R).
  const double lon =
      std::fmod(l, 2.0 * kPi) + kPi - 0.09033 * arcsec + n.dpsi - 20.4898 * arcsec / r_au;
  spherical_to_vector(lon, 0.0, n.eps, r_au * kAu_km, r);
}

/// Table 47.A: multiples of D, M, M', F; longitude (1e-6 deg); distance (1e-3 km).
struct LonDistTerm {
  std::int8_t d, m, mp, f;
  std::int32_t l, r;
};
constexpr LonDistTerm kLonDist[] = {
    {0, 0, 1, 0, 6288774, -20905355},
    {2, 0, -1, 0, 1274027, -3699111},
    {2, 0, 0, 0, 658314, -2955968},
    {0, 0, 2, 0, 213618, -569925},
    {0, 1, 0, 0, -185116, 48888},
    {0, 0, 0, 2, -114332, -3149},
    {2, 0, -2, 0, 58793, 246158},
    {2, -1, -1, 0, 57066, -152138},
    {2, 0, 1, 0, 53322, -170733},
    {2, -1, 0, 0, 45758, -204586},
    {0, 1, -1, 0, -40923, -129620},
    {1, 0, 0, 0, -34720, 108743},
    {0, 1, 1, 0, -30383, 104755},
    {2, 0, 0, -2, 15327, 10321},
    {0, 0, 1, 2, -12528, 0},
    {0, 0, 1, -2, 10980, 79661},
    {4, 0, -1, 0, 10675, -34782},
    {0, 0, 3, 0, 10034, -23210},
    {4, 0, -2, 0, 8548, -21636},
    {2, 1, -1, 0, -7888, 24208},
    {2, 1, 0, 0, -6766, 30824},
    {1, 0, -1, 0, -5163, -8379},
    {1, 1, 0, 0, 4987, -16675},
    {2, -1, 1, 0, 4036, -12831},
    {2, 0, 2, 0, 3994, -10445},
    {4, 0, 0, 0, 3861, -11650},
    {2, 0, -3, 0, 3665, 14403},
    {0, 1, -2, 0, -2689, -7003},
    {2, 0, -1, 2, -2602, 0},
    {2, -1, -2, 0, 2390, 10056},
    {1, 0, 1, 0, -2348, 6322},
    {2, -2, 0, 0, 2236, -9884},
    {0, 1, 2, 0, -2120, 5751},
    {0, 2, 0, 0, -2069, 0},
    {2, -2, -1, 0, 2048, -4950},
    {2, 0, 1, -2, -1773, 4130},
    {2, 0, 0, 2, -1595, 0},
    {4, -1, -1, 0, 1215, -3958},
    {0, 0, 2, 2, -1110, 0},
    {3, 0, -1, 0, -892, 3258},
    {2, 1, 1, 0, -810, 2616},
    {4, -1, -2, 0, 759, -1897},
    {0, 2, -1, 0, -713, -2117},
    {2, 2, -1, 0, -700, 2354},
    {2, 1, -2, 0, 691, 0},
    {2, -1, 0, -2, 596, 0},
    {4, 0, 1, 0, 549, -1423},
    {0, 0, 4, 0, 537, -1117},
    {4, -1, 0, 0, 520, -1571},
    {1, 0, -2, 0, -487, -1739},
    {2, 1, 0, -2, -399, 0},
    {0, 0, 2, -2, -381, -4421},
    {1, 1, 1, 0, 351, 0},
    {3, 0, -2, 0, -340, 0},
    {4, 0, -3, 0, 330, 0},
    {2, -1, 2, 0, 327, 0},
    {0, 2, 1, 0, -323, 1165},
    {1, 1, -1, 0, 299, 0},
    {2, 0, 3, 0, 294, 0},
};

/// Table 47.B, its 30 largest terms: multiples of D, M, M', F; latitude (1e-6 deg).
struct LatTerm {
  std::int8_t d, m, mp, f;
  std::int32_t b;
};
constexpr LatTerm kLat[] = {
    {0, 0, 0, 1, 5128122}, {0, 0, 1, 1, 280602},  {0, 0, 1, -1, 277693}, {2, 0, 0, -1, 173237},
    {2, 0, -1, 1, 55413},  {2, 0, -1, -1, 46271}, {2, 0, 0, 1, 32573},   {0, 0, 2, 1, 17198},
    {2, 0, 1, -1, 9266},   {0, 0, 2, -1, 8822},   {2, -1, 0, -1, 8216},  {2, 0, -2, -1, 4324},
    {2, 0, 1, 1, 4200},    {2, 1, 0, -1, -3359},  {2, -1, -1, 1, 2463},  {2, -1, 0, 1, 2211},
    {2, -1, -1, -1, 2065}, {0, 1, -1, -1, -1870}, {4, 0, -1, -1, 1828},  {0, 1, 0, 1, -1794},
    {0, 0, 0, 3, -1749},   {0, 1, -1, 1, -1565},  {1, 0, 0, 1, -1491},   {0, 1, 1, 1, -1475},
    {0, 1, 1, -1, -1410},  {0, 1, 0, -1, -1344},  {1, 0, 0, -1, -1335},  {0, 0, 3, 1, 1107},
    {4, 0, 0, -1, 1021},   {4, 0, -1, 1, 833},
};

/// cos(k x) and sin(k x) for k = 0..max.
struct Multiples {
  double c[5], s[5];
  Multiples(double x, int max) {
    c[0] = 1.0;
    s[0] = 0.0;
    c[1] = std::cos(x);
    s[1] = std::sin(x);
    for (int k = 2; k <= max; ++k) {
      c[k] = c[k - 1] * c[1] - s[k - 1] * s[1];
      s[k] = s[k - 1] * c[1] + c[k - 1] * s[1];
    }
  }
  /// e^(i n x) for n = -max..max, multiplied into (re, im).
  void times(int n, double& re, double& im) const {
    if (n == 0) return;
    const int k = n < 0 ? -n : n;
    const double cr = c[k], ci = n < 0 ? -s[k] : s[k];
    const double r = re * cr - im * ci;
    im = re * ci + im * cr;
    re = r;
  }
};

void term_cos_sin(const Multiples& d, const Multiples& m, const Multiples& mp, const Multiples& f,
                  int nd, int nm, int nmp, int nf, double& c, double& s) {
  double re = 1.0, im = 0.0;
  d.times(nd, re, im);
  m.times(nm, re, im);
  mp.times(nmp, re, im);
  f.times(nf, re, im);
  c = re;
  s = im;
}

void moon_position(double t, const Nutation& n, double r[3]) {
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
  const double lp =
      218.3164477 + 481267.88123421 * t - 0.0015786 * t2 + t3 / 538841.0 - t4 / 65194000.0;
  const double d =
      rad(297.8501921 + 445267.1114034 * t - 0.0018819 * t2 + t3 / 545868.0 - t4 / 113065000.0);
  const double m = rad(357.5291092 + 35999.0502909 * t - 0.0001536 * t2 + t3 / 24490000.0);
  const double mp =
      rad(134.9633964 + 477198.8675055 * t + 0.0087414 * t2 + t3 / 69699.0 - t4 / 14712000.0);
  const double f =
      rad(93.2720950 + 483202.0175233 * t - 0.0036539 * t2 - t3 / 3526000.0 + t4 / 863310000.0);
  const double a1 = rad(119.75 + 131.849 * t);
  const double a2 = rad(53.09 + 479264.290 * t);
  const double a3 = rad(313.45 + 481266.484 * t);
  const double e = 1.0 - 0.002516 * t - 0.0000074 * t2;

  // Every argument is a sum of small multiples of D, M, M' and F: build
  // e^(i k x) for each by complex multiplication once, then each term costs a
  // few multiplications instead of a sine and a cosine (the M0+ has no FPU).
  Multiples md(d, 4), mm(m, 2), mmp(mp, 4), mf(f, 3);
  double sl = 0.0, sr = 0.0, sb = 0.0;
  for (const LonDistTerm& k : kLonDist) {
    double c, s;
    term_cos_sin(md, mm, mmp, mf, k.d, k.m, k.mp, k.f, c, s);
    const double scale = k.m == 0 ? 1.0 : (k.m == 1 || k.m == -1 ? e : e * e);
    sl += k.l * scale * s;
    sr += k.r * scale * c;
  }
  for (const LatTerm& k : kLat) {
    double c, s;
    term_cos_sin(md, mm, mmp, mf, k.d, k.m, k.mp, k.f, c, s);
    const double scale = k.m == 0 ? 1.0 : (k.m == 1 || k.m == -1 ? e : e * e);
    sb += k.b * scale * s;
  }
  const double lp_rad = rad(lp);
  // Additive terms (Venus, Jupiter, the Earth's flattening).
  sl += 3958 * std::sin(a1) + 1962 * std::sin(lp_rad - f) + 318 * std::sin(a2);
  sb += -2235 * std::sin(lp_rad) + 382 * std::sin(a3) + 175 * std::sin(a1 - f) +
        175 * std::sin(a1 + f) + 127 * std::sin(lp_rad - mp) - 115 * std::sin(lp_rad + mp);

  const double lon = lp_rad + sl * 1e-6 * kDeg + n.dpsi;
  const double lat = sb * 1e-6 * kDeg;
  const double dist_km = 385000.56 + sr / 1000.0;
  spherical_to_vector(lon, lat, n.eps, dist_km, r);
}

}  // namespace

void body_position_tod(Body body, double days_j2000_tt, double r_km[3]) {
  const double t = days_j2000_tt / 36525.0;
  const Nutation n = nutation(t);
  if (body == Body::kSun) {
    sun_position(t, n, r_km);
  } else {
    moon_position(t, n, r_km);
  }
}

double gast_rad(double days_j2000_ut1) {
  const Nutation n = nutation(days_j2000_ut1 / 36525.0);
  return gmst_rad(days_j2000_ut1) + n.dpsi * std::cos(n.eps);
}

EcefState body_ecef(Body body, std::int64_t unix_ms) {
  const double d_ut1 = days_since_j2000(unix_ms);
  const double t = (d_ut1 + kTtMinusUtc_s / 86400.0) / 36525.0;
  // One nutation for the position and the sidereal time (TT and UT1 differ by
  // a minute: 1e-8 of a nutation period).
  const Nutation n = nutation(t);
  double tod[3];
  if (body == Body::kSun) {
    sun_position(t, n, tod);
  } else {
    moon_position(t, n, tod);
  }
  // The body's own motion for the rates: a rotation about the ecliptic pole at
  // its mean rate (Sun 0.9856, Moon 13.176 deg/day). Its eccentricity and the
  // Moon's 5 deg inclination are ignored: under 0.3 % of the az/el rates, which
  // the Earth's rotation dominates; one series evaluation instead of two.
  constexpr double kDegPerDayToRadPerS = kDeg / 86400.0;
  const double rate = (body == Body::kSun ? 0.9856474 : 13.176358) * kDegPerDayToRadPerS;
  const double wy = -std::sin(n.eps) * rate, wz = std::cos(n.eps) * rate;  // the ecliptic pole
  const double v_tod[3] = {wy * tod[2] - wz * tod[1], wz * tod[0], -wy * tod[0]};
  const double g = gmst_rad(d_ut1) + n.dpsi * std::cos(n.eps);
  const double c = std::cos(g), s = std::sin(g);
  EcefState e;
  e.r_km[0] = c * tod[0] + s * tod[1];
  e.r_km[1] = -s * tod[0] + c * tod[1];
  e.r_km[2] = tod[2];
  e.v_km_s[0] = c * v_tod[0] + s * v_tod[1] + kEarthRotationRad_s * e.r_km[1];
  e.v_km_s[1] = -s * v_tod[0] + c * v_tod[1] - kEarthRotationRad_s * e.r_km[0];
  e.v_km_s[2] = v_tod[2];
  return e;
}

}  // namespace rotord::tracking
