#include "bounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rotord::bench {
namespace {

// Distance covered by running t1 then coasting out.
double relay_distance_deg(const BoundPlant& p, double t1_s) {
  const double lag = 1.0 - std::exp(-t1_s / p.tau_m_s);
  const double x_on = p.v_max_deg_s * (t1_s - p.tau_m_s * lag);
  return x_on + p.v_max_deg_s * lag * p.tau_c_s;
}

constexpr double kCoastEndFraction = 0.01;  // coast "ends" at 1 % of v_max

}  // namespace

double trapezoid_bound_s(const BoundPlant& p, double distance_deg) {
  const double a = p.v_max_deg_s / p.tau_m_s;
  const double v = p.v_max_deg_s;
  if (distance_deg >= v * v / a) return distance_deg / v + v / a;
  return 2.0 * std::sqrt(distance_deg / a);
}

double relay_coast_bound_s(const BoundPlant& p, double distance_deg) {
  double lo = 0.0, hi = distance_deg / p.v_max_deg_s + 10.0 * p.tau_m_s + 1.0;
  for (int i = 0; i < 100; ++i) {  // distance grows monotonically with t1
    const double mid = 0.5 * (lo + hi);
    (relay_distance_deg(p, mid) < distance_deg ? lo : hi) = mid;
  }
  const double w = p.v_max_deg_s * (1.0 - std::exp(-lo / p.tau_m_s));
  const double coast_s =
      p.tau_c_s * std::log(std::max(1.0, w / (kCoastEndFraction * p.v_max_deg_s)));
  return lo + coast_s;
}

double relay_brake_bound_s(const BoundPlant& p, double distance_deg) {
  const double b = p.brake_decel_deg_s2;
  auto distance = [&](double t1_s) {
    const double lag = 1.0 - std::exp(-t1_s / p.tau_m_s);
    const double w = p.v_max_deg_s * lag;
    return p.v_max_deg_s * (t1_s - p.tau_m_s * lag) + w * w / (2.0 * b);
  };
  double lo = 0.0, hi = distance_deg / p.v_max_deg_s + 10.0 * p.tau_m_s + 1.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (distance(mid) < distance_deg ? lo : hi) = mid;
  }
  return lo + p.v_max_deg_s * (1.0 - std::exp(-lo / p.tau_m_s)) / b;
}

double max_csv_bound_deviation_s(const char* csv_path, int* rows_checked) {
  std::FILE* f = std::fopen(csv_path, "r");
  *rows_checked = 0;
  if (f == nullptr) return -1.0;
  char line[512];
  double worst = 0.0;
  if (std::fgets(line, sizeof line, f) == nullptr) {  // header
    std::fclose(f);
    return -1.0;
  }
  char profile[64];
  double d, v, a, tm, tc, t_trap, t_bang, t_relay, coast;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::sscanf(line, "%63[^,],%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", profile, &d, &v, &a, &tm,
                    &tc, &t_trap, &t_bang, &t_relay, &coast) != 10)
      continue;
    const BoundPlant p{v, tm, tc};
    // The CSV rounds to 1 ms; a = v / tau_m in every row.
    worst = std::max(worst, std::fabs(trapezoid_bound_s(p, d) - t_trap));
    worst = std::max(worst, std::fabs(relay_coast_bound_s(p, d) - t_relay));
    ++*rows_checked;
  }
  std::fclose(f);
  return worst;
}

}  // namespace rotord::bench
