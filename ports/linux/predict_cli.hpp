#pragma once
#include <string>

namespace CLI {
class App;
}

namespace rotord::linux_port {

/// `rotord predict` and `rotord passes`: the tracking layer on the command
/// line, no daemon. Both print CSV on standard output; bad input gets one line
/// on standard error and exit status 2.
struct PredictOptions {
  std::string tle_file;
  std::string name;  ///< title line of the element set in the file (first set if empty)
  std::string body;  ///< sun or moon, instead of --tle
  double lat_deg = 0, lon_deg = 0, alt_m = 0;
  std::string from, to;  ///< UTC, e.g. 2019-12-09T16:34:30Z
  double step_s = 0;
  double min_el_deg = 0;
};

/// Adds the two subcommands to `app`; returns them so main() can dispatch.
struct PredictCommands {
  CLI::App* predict;
  CLI::App* passes;
};
PredictCommands add_predict_commands(CLI::App& app, PredictOptions& options);

/// utc,az_deg,el_deg,range_km: one row per step from --from to --to, both included.
int run_predict(const PredictOptions& options);
/// aos_utc,los_utc,max_el_deg,max_el_utc,aos_az_deg,los_az_deg for each pass.
int run_passes(const PredictOptions& options);

}  // namespace rotord::linux_port
