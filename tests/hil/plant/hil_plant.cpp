// The simulator's plant (sim/) for the emulated Pico W (make hil): the same
// SimRotator the Linux daemon's --sim runs, driven over a pipe by the node
// harness (tests/hil/lib/plant.mjs), which reads the motor outputs from the
// emulated chip's GPIOs and drives its encoder pin, ADC and switches from the
// replies. One line in, one line out; the harness owns the time: `s` moves
// the plant to an absolute emulated millisecond.
//
//   rotord_hil_plant --profile g5500 [--sensor pot|ma3] [--theta DEG] [--noise on|off]
//                    [--speed-scale K]
//
// Commands (stdin), replies (stdout):
//   s MS CW CCW FAST BRAKE PWM_CW PWM_CCW   outputs held from now on, then advance to MS
//     -> THETA POT_COUNTS MA3_VALID MA3_HIGH_US MA3_LOW_US L_CW L_CCW T1 T2 STALLED
//   set THETA            -> ok     axis at rest at THETA
//   jam SECONDS          -> ok     mechanical jam (-1: for ever)
//   limit cw|ccw 0|1 S   -> ok     a limit switch stuck open/closed for S seconds
//   clear                -> ok     faults cleared
//   settings [KEY=VALUE ...] -> the stored settings document for this profile
//     (the user's layer over the table's defaults, as the firmware saves it),
//     on one line (or "error: ..."), then "end"
//   q                    -> (exits)
// Bad input answers "error: <why>".
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "json/settings_json.hpp"
#include "settings/settings.hpp"
#include "sim/adc_scale.hpp"
#include "sim/fault_window.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace {

using rotord::AxisId;
using rotord::DriveOutputs;
using rotord::Millis;
using rotord::OutputChannel;
namespace sim = rotord::sim;

/// hal::Storage in RAM: catches the document save_settings writes.
class MemoryStorage final : public rotord::hal::Storage {
 public:
  long load(char*, std::size_t) override { return -1; }
  bool save(std::string_view document) override {
    if (document.size() >= sizeof doc_) return false;
    std::memcpy(doc_, document.data(), document.size());
    doc_[document.size()] = '\0';
    return true;
  }
  const char* document() const { return doc_; }

 private:
  char doc_[16384] = "";
};

struct Options {
  const char* profile = "g5500";
  const char* sensor = nullptr;  // the profile's own
  double theta_deg = NAN;        // the profile's start (mid-range)
  bool noise = false;
  double speed_scale = 1.0;
};

bool parse_options(int argc, char** argv, Options& o) {
  for (int n = 1; n < argc; ++n) {
    const std::string_view arg = argv[n];
    if (n + 1 >= argc) return false;
    const char* value = argv[++n];
    if (arg == "--profile") {
      o.profile = value;
    } else if (arg == "--sensor") {
      o.sensor = value;
    } else if (arg == "--theta") {
      o.theta_deg = std::atof(value);
    } else if (arg == "--noise") {
      o.noise = std::string_view(value) == "on";
    } else if (arg == "--speed-scale") {
      o.speed_scale = std::atof(value);
    } else {
      return false;
    }
  }
  return o.speed_scale > 0.0;
}

/// Prints the user's layer of settings the firmware needs for this rotator:
/// the profile's overrides (the same list `rotord --sim` applies), then the
/// command's KEY=VALUE pairs (text form, as a settings file holds them).
void print_settings(const sim::Profile& profile, char* args) {
  static rotord::settings::Settings base;
  static rotord::settings::Settings values;
  values = base;
  for (const sim::SettingOverride& o : profile.overrides) {
    const auto id = rotord::settings::find(o.key);
    if (!id || values.set(*id, o.value).error != rotord::Error::kOk) {
      std::printf("error: the profile sets an invalid %s\n", o.key);
      return;
    }
  }
  for (char* tok = std::strtok(args, " \t\n"); tok != nullptr;
       tok = std::strtok(nullptr, " \t\n")) {
    char* eq = std::strchr(tok, '=');
    if (eq == nullptr) {
      std::printf("error: %s is not KEY=VALUE\n", tok);
      return;
    }
    *eq = '\0';
    const auto id = rotord::settings::find(tok);
    if (!id) {
      std::printf("error: unknown setting %s\n", tok);
      return;
    }
    const auto r = values.set_from_text(*id, eq + 1);
    if (r.error != rotord::Error::kOk) {
      std::printf("error: %s: %s\n", tok, r.reason);
      return;
    }
  }
  static MemoryStorage storage;
  static char buf[16384];
  if (!rotord::web::save_settings(storage, values, base, buf, sizeof buf)) {
    std::printf("error: the settings document does not fit\n");
    return;
  }
  // One line: the harness reads line by line (JSON needs no newlines).
  for (const char* p = storage.document(); *p != '\0'; ++p) std::putchar(*p == '\n' ? ' ' : *p);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (!parse_options(argc, argv, opt)) {
    std::fprintf(stderr,
                 "usage: rotord_hil_plant --profile NAME [--sensor pot|ma3] [--theta DEG] "
                 "[--noise on|off] [--speed-scale K]\n");
    return 2;
  }
  const sim::Profile* base = sim::find_profile(opt.profile);
  if (base == nullptr) {
    std::fprintf(stderr, "rotord_hil_plant: unknown profile %s\n", opt.profile);
    return 2;
  }
  // A copy of the profile with the harness's variations: the sensor fitted
  // and a faster motor (short emulated runs); the model itself is unchanged.
  static sim::Profile profile = *base;
  profile.az.plant.v_max_deg_s *= opt.speed_scale;
  if (opt.sensor != nullptr) {
    const std::string_view s = opt.sensor;
    if (s != "pot" && s != "ma3") {
      std::fprintf(stderr, "rotord_hil_plant: --sensor pot or ma3\n");
      return 2;
    }
    profile.az.sensor = s == "ma3" ? sim::SensorKind::kMa3 : sim::SensorKind::kPot;
  }
  // The overrides follow the sensor and the drive: rebuilt from the axis.
  static sim::SettingOverride overrides[32];
  std::size_t n = 0;
  for (const sim::SettingOverride& o : base->overrides) {
    const std::string_view key = o.key;
    // The harness plays the azimuth only: the elevation is switched off.
    if (key.starts_with("el.") || key.starts_with("az.pot_cal") || key == "az.ma3_zero_deg" ||
        key == "az.sensor")
      continue;
    overrides[n++] = o;
  }
  overrides[n++] = {"el.enabled", 0.0};
  overrides[n++] = {"az.sensor", static_cast<double>(profile.az.sensor)};
  if (profile.az.sensor == sim::SensorKind::kPot) {
    const sim::AxisProfile& a = profile.az;
    overrides[n++] = {"az.pot_cal_lo_counts", sim::adc_counts_exact(a.pot.v_at_min_v)};
    overrides[n++] = {"az.pot_cal_lo_deg", a.min_deg};
    overrides[n++] = {"az.pot_cal_hi_counts", sim::adc_counts_exact(a.pot.v_at_max_v)};
    overrides[n++] = {"az.pot_cal_hi_deg", a.max_deg};
  } else {
    overrides[n++] = {"az.ma3_zero_deg", 0.0};
  }
  profile.overrides = {overrides, n};

  static sim::SimRotator rotator(profile, 1,
                                 opt.noise ? sim::SensorNoise::kOn : sim::SensorNoise::kOff);
  if (!std::isnan(opt.theta_deg)) rotator.set_theta_deg(AxisId::kAz, opt.theta_deg);
  rotord::AxisIo io = rotator.io(AxisId::kAz);
  // Both sensors are read whichever the controller uses: the pot fake is
  // only reachable through io when the profile fits a pot.
  sim::SimPot pot(
      rotator.plant(AxisId::kAz),
      {.v0_v = profile.az.pot.v0_v(profile.az.min_deg, profile.az.max_deg),
       .k_v_per_deg = profile.az.pot.k_v_per_deg(profile.az.min_deg, profile.az.max_deg),
       .sigma_v = opt.noise ? profile.az.pot.sigma_v : 0.0},
      7);
  sim::SimMa3 ma3(rotator.plant(AxisId::kAz), opt.noise ? profile.az.ma3_sigma_deg : 0.0, 9);

  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  char line[2048];
  while (std::fgets(line, sizeof line, stdin) != nullptr) {
    if (line[0] == 's' && line[1] == ' ') {
      long ms = 0;
      double cw = 0, ccw = 0, fast = 0, brake = 0, pwm_cw = 0, pwm_ccw = 0;
      if (std::sscanf(line + 2, "%ld %lf %lf %lf %lf %lf %lf", &ms, &cw, &ccw, &fast, &brake,
                      &pwm_cw, &pwm_ccw) != 7) {
        std::printf("error: s MS CW CCW FAST BRAKE PWM_CW PWM_CCW\n");
        continue;
      }
      DriveOutputs out;
      out.set(OutputChannel::kRelayCw, static_cast<float>(cw));
      out.set(OutputChannel::kRelayCcw, static_cast<float>(ccw));
      out.set(OutputChannel::kSpeedFast, static_cast<float>(fast));
      out.set(OutputChannel::kVoltageFast, static_cast<float>(fast));
      out.set(OutputChannel::kBrake, static_cast<float>(brake));
      out.set(OutputChannel::kPwmCw, static_cast<float>(pwm_cw));
      out.set(OutputChannel::kPwmCcw, static_cast<float>(pwm_ccw));
      io.drive->apply(out);
      rotator.advance_to(Millis{ms});
      const double now_s = rotator.plant(AxisId::kAz).time_s();
      pot.update(now_s);
      ma3.update(now_s);
      const rotord::hal::PwmPeriod period = ma3.read();
      auto closed = [](rotord::hal::DigitalIn* in) {
        return in != nullptr && in->active() ? 1 : 0;
      };
      std::printf("%.4f %u %d %u %u %d %d %d %d %d\n", rotator.plant(AxisId::kAz).theta_deg(),
                  static_cast<unsigned>(pot.read_counts()), period.valid ? 1 : 0,
                  static_cast<unsigned>(period.high_us), static_cast<unsigned>(period.low_us),
                  closed(io.limit_cw), closed(io.limit_ccw), closed(io.t1), closed(io.t2),
                  rotator.plant(AxisId::kAz).stalled() ? 1 : 0);
    } else if (std::strncmp(line, "set ", 4) == 0) {
      rotator.set_theta_deg(AxisId::kAz, std::atof(line + 4));
      ma3.sample();
      std::printf("ok\n");
    } else if (std::strncmp(line, "jam ", 4) == 0) {
      const double s = std::atof(line + 4);
      rotator.jam(AxisId::kAz, s < 0 ? sim::kForever_s : s);
      std::printf("ok\n");
    } else if (std::strncmp(line, "limit ", 6) == 0) {
      char which[8] = "";
      int state = 0;
      double s = 0;
      if (std::sscanf(line + 6, "%7s %d %lf", which, &state, &s) != 3 ||
          (std::strcmp(which, "cw") != 0 && std::strcmp(which, "ccw") != 0)) {
        std::printf("error: limit cw|ccw 0|1 SECONDS\n");
        continue;
      }
      rotator.limit_switch_stuck(AxisId::kAz, std::strcmp(which, "cw") == 0, state != 0,
                                 s < 0 ? sim::kForever_s : s);
      std::printf("ok\n");
    } else if (std::strncmp(line, "clear", 5) == 0) {
      rotator.clear_faults(AxisId::kAz);
      std::printf("ok\n");
    } else if (std::strncmp(line, "settings", 8) == 0) {
      print_settings(profile, line + 8);
      std::printf("end\n");
    } else if (line[0] == 'q') {
      return 0;
    } else {
      std::printf("error: unknown command\n");
    }
  }
  return 0;
}
