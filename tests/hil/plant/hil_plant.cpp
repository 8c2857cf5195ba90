// The simulator's plant (sim/) for the emulated Pico W (make hil): the same
// SimRotator the Linux daemon's --sim runs, driven over a pipe by the node
// harness (tests/hil/lib/plant.mjs), which reads the motor outputs from the
// emulated chip's GPIOs and drives its encoder pin, ADC and switches from the
// replies. One line in, one line out; the harness owns the time: `s` moves
// the plant to an absolute emulated millisecond.
//
//   rotord_hil_plant --profile g5500 [--sensor pot|ma3] [--theta DEG] [--noise on|off]
//                    [--speed-scale K] [--el pot|ma3] [--theta-el DEG] [--pot-samples N]
//                    [--drive relay|relay_two_speed|relay_voltage_select|hbridge] [--mag on]
//
// Without --el the harness plays the azimuth only (el.enabled = 0 in the
// settings it prints); with it, the profile's elevation too, on its own pins.
// --noise on: the simulator's sensor noise (seeded, so every run is the same).
// --drive: the azimuth's drive instead of the profile's (the motor model
// and az.drive together: a two-speed or voltage-select G-5500, say, where
// FAST selects the fast winding or supply and the slow one runs at half speed).
// --mag on: a QMC5883L on the azimuth (sim::SimMag, its noise with --noise):
// each `s` reply ends in MAG=<its 14 registers 0x00..0x0D, hex>, which the
// harness serves to the firmware over the emulated I2C.
// --pot-samples N: each pot's POT field is N conversions, comma-separated,
// each with its own noise (the firmware converts az.pot_samples times per
// tick and takes the median: one value repeated would defeat that filter).
//
// Commands (stdin), replies (stdout):
//   s MS CW CCW FAST BRAKE PWM_CW PWM_CCW [UP DOWN EL_FAST PWM_UP PWM_DOWN]
//       outputs held from now on (the elevation's with --el), then advance to MS
//     -> THETA POT_COUNTS MA3_VALID MA3_HIGH_US MA3_LOW_US L_CW L_CCW T1 T2 STALLED
//        and with --el: EL_THETA EL_POT EL_MA3_VALID EL_MA3_HIGH EL_MA3_LOW L_UP L_DOWN EL_STALLED
//        and with --mag: MAG=<28 hex digits>
//   set [az|el] THETA    -> ok     axis at rest at THETA
//   jam [az|el] SECONDS  -> ok     mechanical jam (-1: for ever)
//   limit [az|el] cw|ccw 0|1 S -> ok  a limit switch stuck open/closed for S seconds
//                                     (on the elevation cw is UP, ccw DOWN)
//   slip [az|el] SPEED_DEG_S S -> ok  the wind turns the unpowered antenna
//                                     against its brake at SPEED_DEG_S for S
//                                     seconds (sim::AxisPlant::wind_slip)
//   sensor [az|el] loss|stuck S -> ok  the position sensor fails for S seconds
//                                     (-1: for ever): loss is an open pot wiper
//                                     (0 counts) and an MA3 without pulses, stuck
//                                     freezes both at their present reading
//   sensor [az|el] burst SIGMA_DEG S -> ok  sensor noise raised to SIGMA_DEG
//   clear [az|el]        -> ok     faults cleared (the sensors' too)
//   settings [KEY=VALUE ...] -> the stored settings document for this profile
//     (the user's layer over the table's defaults, as the firmware saves it),
//     on one line (or "error: ..."), then "end"
//   q                    -> (exits)
// Bad input answers "error: <why>".
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "json/settings_json.hpp"
#include "settings/settings.hpp"
#include "sim/fault_window.hpp"
#include "sim/profiles.hpp"
#include "sim/sensor_overrides.hpp"
#include "sim/sensors.hpp"
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
  const char* el_sensor = nullptr;  // null: the elevation is switched off
  double theta_el_deg = NAN;        // the profile's start (parked at its minimum)
  int pot_samples = 1;              // conversions per pot per reply
  int drive = -1;                   // az.drive's index; -1: the profile's
  bool mag = false;                 // a QMC5883L on the azimuth
};

// az.drive's values, in the settings table's order (core/settings/axis_settings.def).
constexpr std::array<std::string_view, 4> kDriveNames{"relay", "relay_two_speed",
                                                      "relay_voltage_select", "hbridge"};
constexpr std::array<sim::DriveKind, 4> kDriveKinds{
    sim::DriveKind::kRelay, sim::DriveKind::kRelayTwoSpeed, sim::DriveKind::kRelayVoltageSelect,
    sim::DriveKind::kHBridge};

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
    } else if (arg == "--el") {
      o.el_sensor = value;
    } else if (arg == "--theta-el") {
      o.theta_el_deg = std::atof(value);
    } else if (arg == "--pot-samples") {
      o.pot_samples = std::atoi(value);
    } else if (arg == "--mag") {
      o.mag = std::string_view(value) == "on";
    } else if (arg == "--drive") {
      for (std::size_t i = 0; i < kDriveNames.size(); ++i)
        if (kDriveNames[i] == value) o.drive = static_cast<int>(i);
      if (o.drive < 0) return false;
    } else {
      return false;
    }
  }
  return o.speed_scale > 0.0 && o.pot_samples >= 1 && o.pot_samples <= 32;
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

/// The sensor a --sensor / --el option names; false when it is neither.
bool parse_sensor(const char* text, rotord::SensorType& kind) {
  const std::string_view s = text;
  if (s != "pot" && s != "ma3") return false;
  kind = s == "ma3" ? rotord::SensorType::kMa3 : rotord::SensorType::kPot;
  return true;
}

/// Both sensors of one axis, read whichever the controller uses (the
/// rotator's own are only reachable through io when the profile fits them).
struct AxisSensors {
  AxisSensors(sim::AxisPlant& plant, const sim::AxisProfile& a, bool noise, std::uint64_t seed)
      : pot(plant,
            {.v0_v = a.pot.v0_v(a.min_deg, a.max_deg),
             .k_v_per_deg = a.pot.k_v_per_deg(a.min_deg, a.max_deg),
             .sigma_v = noise ? a.pot.sigma_v : 0.0},
            seed),
        ma3(plant, noise ? a.ma3_sigma_deg : 0.0, seed + 2) {}
  sim::SimPot pot;
  sim::SimMa3 ma3;
};

int closed(rotord::hal::DigitalIn* in) {
  return in != nullptr && in->active() ? 1 : 0;
}

/// One axis's part of the `s` reply: angle, pot code, MA3 frame, its two end switches.
void print_axis(sim::SimRotator& rotator, AxisId axis, AxisSensors& sensors, int pot_samples) {
  const double now_s = rotator.plant(axis).time_s();
  sensors.pot.update(now_s);
  sensors.ma3.update(now_s);
  const rotord::hal::PwmPeriod period = sensors.ma3.read();
  const rotord::AxisIo io = rotator.io(axis);
  std::printf("%.4f ", rotator.plant(axis).theta_deg());
  for (int i = 0; i < pot_samples; ++i)
    std::printf(i == 0 ? "%u" : ",%u", static_cast<unsigned>(sensors.pot.read_counts()));
  std::printf(" %d %u %u %d %d", period.valid ? 1 : 0, static_cast<unsigned>(period.high_us),
              static_cast<unsigned>(period.low_us), closed(io.limit_cw), closed(io.limit_ccw));
}

/// `az`/`el` at the start of a command's arguments (skipped); the azimuth when absent.
AxisId parse_axis(const char*& args) {
  while (*args == ' ') ++args;
  if (std::strncmp(args, "el", 2) == 0 && (args[2] == ' ' || args[2] == '\n' || args[2] == '\0')) {
    args += 2;
    return AxisId::kEl;
  }
  if (std::strncmp(args, "az", 2) == 0 && (args[2] == ' ' || args[2] == '\n' || args[2] == '\0'))
    args += 2;
  return AxisId::kAz;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  if (!parse_options(argc, argv, opt)) {
    std::fprintf(stderr,
                 "usage: rotord_hil_plant --profile NAME [--sensor pot|ma3] [--theta DEG] "
                 "[--noise on|off] [--speed-scale K] [--el pot|ma3] [--theta-el DEG] "
                 "[--pot-samples N] [--drive relay|relay_two_speed|relay_voltage_select|hbridge] "
                 "[--mag on]\n");
    return 2;
  }
  const sim::Profile* base = sim::find_profile(opt.profile);
  if (base == nullptr) {
    std::fprintf(stderr, "rotord_hil_plant: unknown profile %s\n", opt.profile);
    return 2;
  }
  // A copy of the profile with the harness's variations: the sensors fitted
  // and faster motors (short emulated runs); the model itself is unchanged.
  static sim::Profile profile = *base;
  profile.az.plant.v_max_deg_s *= opt.speed_scale;
  profile.el.plant.v_max_deg_s *= opt.speed_scale;
  if (opt.sensor != nullptr && !parse_sensor(opt.sensor, profile.az.sensor)) {
    std::fprintf(stderr, "rotord_hil_plant: --sensor pot or ma3\n");
    return 2;
  }
  const bool play_el = opt.el_sensor != nullptr;
  if (play_el && (!base->has_el || !parse_sensor(opt.el_sensor, profile.el.sensor))) {
    std::fprintf(stderr, "rotord_hil_plant: --el pot or ma3, on a profile with an elevation\n");
    return 2;
  }
  // The overrides follow the sensors and the drives: rebuilt from the axes.
  static sim::SettingOverride overrides[48];
  std::size_t n = 0;
  for (const sim::SettingOverride& o : base->overrides) {
    const std::string_view key = o.key;
    if (sim::is_sensor_key(key, sim::kAzSensorKeys) || sim::is_sensor_key(key, sim::kElSensorKeys))
      continue;
    if (key == "az.drive" && opt.drive >= 0) continue;
    // Without --el the harness plays the azimuth only: the elevation is switched off.
    if (key.starts_with("el.") && !play_el) continue;
    overrides[n++] = o;
  }
  if (!play_el) overrides[n++] = {"el.enabled", 0.0};
  if (opt.drive >= 0) {
    profile.az.plant.drive = kDriveKinds[static_cast<std::size_t>(opt.drive)];
    overrides[n++] = {"az.drive", static_cast<double>(opt.drive)};
  }
  sim::add_sensor_overrides(profile.az, sim::kAzSensorKeys, overrides, n);
  if (play_el) sim::add_sensor_overrides(profile.el, sim::kElSensorKeys, overrides, n);
  profile.overrides = {overrides, n};

  static sim::SimRotator rotator(profile, 1,
                                 opt.noise ? sim::SensorNoise::kOn : sim::SensorNoise::kOff);
  if (!std::isnan(opt.theta_deg)) rotator.set_theta_deg(AxisId::kAz, opt.theta_deg);
  if (play_el && !std::isnan(opt.theta_el_deg))
    rotator.set_theta_deg(AxisId::kEl, opt.theta_el_deg);
  rotord::AxisIo io = rotator.io(AxisId::kAz);
  rotord::AxisIo el_io = rotator.io(AxisId::kEl);
  AxisSensors az_sensors(rotator.plant(AxisId::kAz), profile.az, opt.noise, 7);
  AxisSensors el_sensors(rotator.plant(AxisId::kEl), profile.el, opt.noise, 11);
  // The QMC5883L's noise, when on: a few counts, as the simulator's own.
  sim::SimMag mag(rotator.plant(AxisId::kAz), opt.noise ? 3.0 : 0.0, 13);
  auto sensors = [&](AxisId axis) -> AxisSensors& {
    return axis == AxisId::kEl ? el_sensors : az_sensors;
  };

  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  char line[2048];
  while (std::fgets(line, sizeof line, stdin) != nullptr) {
    if (line[0] == 's' && line[1] == ' ') {
      long ms = 0;
      double u[12] = {};
      const int got =
          std::sscanf(line + 2, "%ld %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", &ms, &u[0],
                      &u[1], &u[2], &u[3], &u[4], &u[5], &u[6], &u[7], &u[8], &u[9], &u[10]);
      if (got != 7 && !(got == 12 && play_el)) {
        std::printf(
            "error: s MS CW CCW FAST BRAKE PWM_CW PWM_CCW [UP DOWN FAST PWM_UP PWM_DOWN]\n");
        continue;
      }
      auto outputs = [](double cw, double ccw, double fast, double brake, double pwm_cw,
                        double pwm_ccw) {
        DriveOutputs out;
        out.set(OutputChannel::kRelayCw, static_cast<float>(cw));
        out.set(OutputChannel::kRelayCcw, static_cast<float>(ccw));
        out.set(OutputChannel::kSpeedFast, static_cast<float>(fast));
        out.set(OutputChannel::kVoltageFast, static_cast<float>(fast));
        out.set(OutputChannel::kBrake, static_cast<float>(brake));
        out.set(OutputChannel::kPwmCw, static_cast<float>(pwm_cw));
        out.set(OutputChannel::kPwmCcw, static_cast<float>(pwm_ccw));
        return out;
      };
      io.drive->apply(outputs(u[0], u[1], u[2], u[3], u[4], u[5]));
      if (got == 12) el_io.drive->apply(outputs(u[6], u[7], u[8], 0, u[9], u[10]));
      rotator.advance_to(Millis{ms});
      print_axis(rotator, AxisId::kAz, az_sensors, opt.pot_samples);
      std::printf(" %d %d %d", closed(io.t1), closed(io.t2),
                  rotator.plant(AxisId::kAz).stalled() ? 1 : 0);
      if (play_el) {
        std::printf(" ");
        print_axis(rotator, AxisId::kEl, el_sensors, opt.pot_samples);
        std::printf(" %d", rotator.plant(AxisId::kEl).stalled() ? 1 : 0);
      }
      if (opt.mag) {
        const std::uint8_t first = 0x00;
        std::uint8_t regs[14] = {};
        mag.write_read(sim::SimMag::kAddress, &first, 1, regs, sizeof regs);
        std::printf(" MAG=");
        for (const std::uint8_t r : regs) std::printf("%02x", r);
      }
      std::printf("\n");
    } else if (std::strncmp(line, "set ", 4) == 0) {
      const char* args = line + 4;
      const AxisId axis = parse_axis(args);
      rotator.set_theta_deg(axis, std::atof(args));
      sensors(axis).ma3.sample();
      std::printf("ok\n");
    } else if (std::strncmp(line, "jam ", 4) == 0) {
      const char* args = line + 4;
      const AxisId axis = parse_axis(args);
      const double s = std::atof(args);
      rotator.jam(axis, s < 0 ? sim::kForever_s : s);
      std::printf("ok\n");
    } else if (std::strncmp(line, "slip ", 5) == 0) {
      const char* args = line + 5;
      const AxisId axis = parse_axis(args);
      double speed_deg_s = 0;
      double s = 0;
      if (std::sscanf(args, "%lf %lf", &speed_deg_s, &s) != 2 || speed_deg_s == 0) {
        std::printf("error: slip [az|el] SPEED_DEG_S SECONDS\n");
        continue;
      }
      rotator.wind_slip(axis, speed_deg_s, s < 0 ? sim::kForever_s : s);
      std::printf("ok\n");
    } else if (std::strncmp(line, "limit ", 6) == 0) {
      char which[8] = "";
      int state = 0;
      double s = 0;
      const char* args = line + 6;
      const AxisId axis = parse_axis(args);
      if (std::sscanf(args, "%7s %d %lf", which, &state, &s) != 3 ||
          (std::strcmp(which, "cw") != 0 && std::strcmp(which, "ccw") != 0)) {
        std::printf("error: limit [az|el] cw|ccw 0|1 SECONDS\n");
        continue;
      }
      rotator.limit_switch_stuck(axis, std::strcmp(which, "cw") == 0, state != 0,
                                 s < 0 ? sim::kForever_s : s);
      std::printf("ok\n");
    } else if (std::strncmp(line, "sensor ", 7) == 0) {
      char which[8] = "";
      double s = 0;
      const char* args = line + 7;
      AxisSensors& axis_sensors = sensors(parse_axis(args));
      double sigma_deg = 0;
      const bool burst = std::sscanf(args, "%7s %lf %lf", which, &sigma_deg, &s) == 3 &&
                         std::strcmp(which, "burst") == 0 && sigma_deg > 0;
      if (!burst && (std::sscanf(args, "%7s %lf", which, &s) != 2 ||
                     (std::strcmp(which, "loss") != 0 && std::strcmp(which, "stuck") != 0))) {
        std::printf("error: sensor [az|el] loss|stuck SECONDS or burst SIGMA_DEG SECONDS\n");
        continue;
      }
      const double duration_s = s < 0 ? sim::kForever_s : s;
      if (burst) {
        axis_sensors.pot.inject_noise_burst(
            sigma_deg * std::fabs(axis_sensors.pot.config().k_v_per_deg), duration_s);
        axis_sensors.ma3.inject_noise_burst(sigma_deg, duration_s);
      } else if (std::strcmp(which, "loss") == 0) {
        axis_sensors.pot.inject_loss(duration_s);
        axis_sensors.ma3.inject_loss(duration_s);
      } else {
        axis_sensors.pot.inject_stuck(duration_s);
        axis_sensors.ma3.inject_stuck(duration_s);
      }
      std::printf("ok\n");
    } else if (std::strncmp(line, "clear", 5) == 0) {
      const char* args = line + 5;
      const AxisId axis = parse_axis(args);
      rotator.clear_faults(axis);
      sensors(axis).pot.clear_faults();
      sensors(axis).ma3.clear_faults();
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
