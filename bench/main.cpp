// rotord_bench: the in-process benchmarks (control quality on the simulator
// in virtual time, the bound check, tick cost). Writes a JSON list of
// {"name", "inputs", "metrics"} rows; bench/run.py adds the rest and prints
// the table. Benchmarks print numbers; no test asserts on them.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "bounds.hpp"
#include "care.hpp"
#include "client_passes.hpp"
#include "commissioning.hpp"
#include "control_quality.hpp"
#include "results.hpp"
#include "tick_cost.hpp"
#include "tracking_error.hpp"
#include "tracking_mode.hpp"

int main(int argc, char** argv) {
  using namespace rotord::bench;
  const char* out_path = nullptr;
  // --only GROUP[,GROUP]: run only these groups (bounds, control, tracking,
  // tracking_mode, clients, care, commissioning, tick), e.g. to measure one change quickly.
  const char* only = nullptr;
  for (int i = 1; i < argc; ++i) {
    const bool ticks = std::strcmp(argv[i], "--ticks") == 0;
    if ((ticks || std::strcmp(argv[i], "--sim-only") == 0) && i + 1 < argc) {
      run_steps_only(std::atol(argv[i + 1]), ticks);  // for callgrind
      return 0;
    }
    if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) out_path = argv[++i];
    if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) only = argv[++i];
    if (std::strcmp(argv[i], "--care") == 0) {  // the day unattended alone
      write_json(stdout, run_care_day());
      return 0;
    }
  }
  const auto wanted = [only](const char* group) {
    if (only == nullptr) return true;
    const std::size_t n = std::strlen(group);
    for (const char* p = only; (p = std::strstr(p, group)) != nullptr; p += n) {
      const bool starts = p == only || p[-1] == ',';
      if (starts && (p[n] == '\0' || p[n] == ',')) return true;
    }
    return false;
  };
  std::vector<Result> results;
  int rows = 0;
  if (wanted("bounds")) {
    const double dev_s =
        max_csv_bound_deviation_s(ROTORD_BENCH_DATA_DIR "/time_optimal_bounds.csv", &rows);
    results.push_back(
        {"bounds/csv_check", {{"rows", static_cast<double>(rows)}}, {{"max_deviation_s", dev_s}}});
    if (dev_s < 0 || dev_s > 0.002) {
      std::fprintf(stderr, "bench: bound formulas disagree with time_optimal_bounds.csv (%.4f s)\n",
                   dev_s);
      return 1;
    }
  }
  const auto add = [&results](std::vector<Result> rows_of_group) {
    for (Result& r : rows_of_group) results.push_back(std::move(r));
  };
  if (wanted("control")) add(run_control_quality());
  if (wanted("tracking")) add(run_tracking_error());
  if (wanted("tracking_mode")) add(run_tracking_mode());
  if (wanted("clients")) add(run_client_passes());
  if (wanted("care")) add(run_care_day());
  if (wanted("commissioning")) add(run_commissioning());
  if (wanted("tick")) results.push_back(run_tick_cost());
  std::FILE* out = out_path ? std::fopen(out_path, "w") : stdout;
  if (out == nullptr) {
    std::perror(out_path);
    return 1;
  }
  write_json(out, results);
  if (out != stdout) std::fclose(out);
  return 0;
}
