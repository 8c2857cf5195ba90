#include "predict_cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "tracking/julian.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/sky_target.hpp"

namespace rotord::linux_port {
namespace {

using tracking::Sgp4Error;

constexpr int kBadInput = 2;
/// More rows than anyone plots: a typo in --step or the dates, not a request.
constexpr std::int64_t kMaxRows = 10'000'000;
constexpr std::streamsize kMaxTleFileBytes = 64 << 20;

int fail(const std::string& message) {
  std::fprintf(stderr, "rotord: %s\n", message.c_str());
  return kBadInput;
}

std::string utc_text(std::int64_t unix_ms) {
  char buf[32];
  return tracking::format_utc_seconds(unix_ms, buf, sizeof buf) > 0 ? buf : "?";
}

/// Sets up the target, observer and window from the options, or says why not.
struct Setup {
  tracking::SkyTarget target;
  tracking::Observer observer;
  std::int64_t from_ms = 0, to_ms = 0;
};

int prepare(const PredictOptions& o, Setup& s) {
  if (!tracking::parse_utc(o.from, s.from_ms))
    return fail("--from: not a UTC time like 2019-12-09T16:34:30Z: '" + o.from + "'");
  if (!tracking::parse_utc(o.to, s.to_ms))
    return fail("--to: not a UTC time like 2019-12-09T16:34:30Z: '" + o.to + "'");
  if (s.to_ms < s.from_ms) return fail("--to is before --from");
  s.observer = tracking::Observer(tracking::Geodetic{o.lat_deg, o.lon_deg, o.alt_m});
  if (!o.body.empty()) {
    s.target.set_body(o.body == "sun" ? tracking::Body::kSun : tracking::Body::kMoon);
    return 0;
  }
  std::ifstream in(o.tle_file, std::ios::binary);
  if (!in) return fail("--tle: cannot read '" + o.tle_file + "'");
  // Read at most the limit plus one byte: a bigger file (or /dev/zero) is refused.
  std::string text;
  char chunk[65536];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > static_cast<std::size_t>(kMaxTleFileBytes))
      return fail("--tle: '" + o.tle_file + "' is over 64 MiB");
  }
  if (in.bad()) return fail("--tle: cannot read '" + o.tle_file + "'");  // e.g. a directory
  tracking::Tle tle;
  const tracking::TleResult r = tracking::find_tle(text, o.name, tle);
  if (r.error == tracking::TleError::kNoElements) {
    return fail(o.name.empty()
                    ? "--tle: no two-line element set in '" + o.tle_file + "'"
                    : "--name: no element set titled '" + o.name + "' in '" + o.tle_file + "'");
  }
  if (!r.ok()) {
    return fail("--tle: bad element set" + (o.name.empty() ? "" : " '" + o.name + "'") + ": " +
                tracking::tle_error_name(r.error) +
                (*r.field ? std::string(" (") + r.field + ")" : ""));
  }
  const Sgp4Error e = s.target.set_satellite(tle);
  if (e != Sgp4Error::kOk)
    return fail("--tle: SGP4 refuses the elements at their epoch: " +
                std::string(tracking::sgp4_error_name(e)));
  return 0;
}

std::string object_name(const PredictOptions& o, const tracking::SkyTarget& t) {
  if (!o.body.empty()) return o.body;
  return t.tle().name[0] ? t.tle().name : std::to_string(t.tle().catalog);
}

}  // namespace

PredictCommands add_predict_commands(CLI::App& app, PredictOptions& o) {
  PredictCommands c{};
  c.predict = app.add_subcommand(
      "predict",
      "Print where a satellite, the Sun or the Moon is (CSV utc,az_deg,el_deg,range_km)");
  c.passes = app.add_subcommand(
      "passes",
      "Print the passes above --min-el (CSV aos_utc,los_utc,max_el_deg,max_el_utc,aos_az_deg,"
      "los_az_deg)");
  for (CLI::App* sub : {c.predict, c.passes}) {
    auto* tle = sub->add_option("--tle", o.tle_file,
                                "File of two- or three-line element sets (CelesTrak format)");
    sub->add_option("--name", o.name, "Title of the element set in the file (default: the first)")
        ->needs(tle);
    auto* body = sub->add_option("--body", o.body, "sun or moon instead of --tle")
                     ->check(CLI::IsMember({"sun", "moon"}))
                     ->excludes(tle);
    tle->excludes(body);
    sub->add_option("--lat", o.lat_deg, "Observer latitude, deg (north positive, WGS-84)")
        ->required()
        ->check(CLI::Range(-90.0, 90.0));
    sub->add_option("--lon", o.lon_deg, "Observer longitude, deg (east positive)")
        ->required()
        ->check(CLI::Range(-180.0, 180.0));
    sub->add_option("--alt", o.alt_m, "Observer height above the WGS-84 ellipsoid, m")
        ->required()
        ->check(CLI::Range(-500.0, 100000.0));
    sub->add_option("--from", o.from, "Start, UTC (2019-12-09T16:34:30Z)")->required();
    sub->add_option("--to", o.to, "End, UTC")->required();
  }
  c.predict->add_option("--step", o.step_s, "Seconds between rows (at least 1)")
      ->required()
      ->check(CLI::Range(1.0, 1e9));
  c.passes->add_option("--min-el", o.min_el_deg, "Minimum elevation of a pass, deg (default 0)")
      ->check(CLI::Range(-90.0, 90.0));
  return c;
}

int run_predict(const PredictOptions& o) {
  if (o.tle_file.empty() && o.body.empty())
    return fail("predict: give --tle FILE or --body sun|moon");
  Setup s;
  if (const int rc = prepare(o, s)) return rc;
  const auto step_ms = static_cast<std::int64_t>(std::llround(o.step_s * 1000.0));
  if ((s.to_ms - s.from_ms) / step_ms + 2 > kMaxRows)
    return fail("predict: more than 10 million rows; use a larger --step or a shorter span");
  // Compute every row before printing any, so an error leaves no partial table.
  std::string out = "utc,az_deg,el_deg,range_km\n";
  for (std::int64_t t = s.from_ms;; t += step_ms) {
    if (t > s.to_ms) t = s.to_ms;
    tracking::LookAngles look;
    const Sgp4Error e = s.target.look(t, s.observer, look);
    if (e != Sgp4Error::kOk)
      return fail(object_name(o, s.target) + ": SGP4 fails at " + utc_text(t) + ": " +
                  tracking::sgp4_error_name(e));
    char row[96];
    std::snprintf(row, sizeof row, "%s,%.3f,%.3f,%.3f\n", utc_text(t).c_str(), look.az_deg,
                  look.el_deg, look.range_km);
    out += row;
    if (t == s.to_ms) break;
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}

int run_passes(const PredictOptions& o) {
  if (o.tle_file.empty() && o.body.empty())
    return fail("passes: give --tle FILE or --body sun|moon");
  Setup s;
  if (const int rc = prepare(o, s)) return rc;
  tracking::PassFinder finder;
  finder.start(s.target, s.observer, s.from_ms, s.to_ms, o.min_el_deg);
  std::string out = "aos_utc,los_utc,max_el_deg,max_el_utc,aos_az_deg,los_az_deg\n";
  for (;;) {
    const tracking::PassFinder::Status status = finder.step(1000);
    if (status == tracking::PassFinder::Status::kError)
      return fail(object_name(o, s.target) +
                  ": SGP4 fails in the window: " + tracking::sgp4_error_name(finder.error()));
    if (status == tracking::PassFinder::Status::kDone) break;
    if (status != tracking::PassFinder::Status::kFound) continue;
    const tracking::Pass& p = finder.pass();
    char row[160];
    std::snprintf(row, sizeof row, "%s,%s,%.3f,%s,%.3f,%.3f\n", utc_text(p.aos_ms).c_str(),
                  utc_text(p.los_ms).c_str(), p.max_el_deg, utc_text(p.max_el_ms).c_str(),
                  p.aos_az_deg, p.los_az_deg);
    out += row;
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}

}  // namespace rotord::linux_port
