#include "settings/rotator_models.hpp"

#include <array>

namespace rotord::settings {
namespace {

// The values of az.drive and az.sensor (axis_settings.def).
constexpr double kRelay = 0;
constexpr double kHBridge = 3;
constexpr double kPot = 0;

constexpr ModelFigure kUnknown{};
constexpr ModelFigure fig(double value, const char* source) {
  return ModelFigure{value, source};
}

// One row per model. A source key ([Y2], [HG14] ...) is explained in
// docs/rotator_models.md; a figure without one was not found, so applying
// the model keeps the setting and self-commissioning measures it. Speeds:
// the maker's time for a turn, as deg/s.
constexpr RotatorModel kModels[] = {
    RotatorModel{"yaesu-g5500", "Yaesu G-5500", fig(kRelay, "[Y6] R/U/L/D control lines"),
                 fig(kPot, "[Y4][Y5] 500 ohm pot"), fig(0, "[Y1][Y2] 0 = most CCW"),
                 fig(450, "[Y1][Y2] 450 deg"), fig(1, "[Y2] az/el"), fig(0, "[Y2] 0-180"),
                 fig(180, "[Y2] 0-180"), kUnknown, kUnknown,
                 fig(0, "[Y6] no brake line on the control connector"), kUnknown, kUnknown,
                 kUnknown,
                 "Owners measure 0.05-4.1 V at the pot output: calibrate both ends [Y5]."},
    RotatorModel{"yaesu-g5500dc", "Yaesu G-5500DC", fig(kRelay, "[Y6] R/U/L/D control lines"),
                 kUnknown, fig(0, "[Y3] north at 0"), fig(450, "[Y3] 450 deg"),
                 fig(1, "[Y3] az/el"), kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown,
                 "DC motors; the oldest GS-232 assumes a north-centred 360 deg [Y3]."},
    RotatorModel{"yaesu-g450", "Yaesu G-450A/C/XL", fig(kRelay, "[Y8] AC motor"),
                 fig(kPot, "[Y8] pot"), fig(0, "[Y8] 0-450"), fig(450, "[Y8] 0-450"),
                 fig(0, "[Y8] azimuth only"), kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown, kUnknown,
                 "The XL has no external control connector: wire to the front switches [Y9]."},
    RotatorModel{"yaesu-g650", "Yaesu G-650 (XL)", kUnknown, kUnknown, kUnknown, kUnknown,
                 fig(0, "[Y8] azimuth-only series"), kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown, kUnknown, kUnknown,
                 "No figure found: self-commissioning measures the travel and speed."},
    RotatorModel{"yaesu-g1000dxa", "Yaesu G-1000DXA", fig(kRelay, "[C2] R/L control pins"),
                 fig(kPot, "[C2] pot, analog out on DIN pin 4"), kUnknown, kUnknown,
                 fig(0, "[Y2] azimuth"), kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown,
                 "Travel 360 or 450 deg by controller type [Y2]: commissioning finds the stops. "
                 "Speed is set on the control box (4 steps via GS-232 [Y11])."},
    RotatorModel{"yaesu-g2800dxa", "Yaesu G-2800DXA", fig(kRelay, "[C2] R/L control pins"),
                 fig(kPot, "[Y13] pot"), fig(0, "[Y12] 0-450"), fig(450, "[Y12] 0-450"),
                 fig(0, "[Y12] azimuth"), kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown, kUnknown,
                 "DC motor, variable voltage [Y13]; series diodes in the motor path [Y14]."},
    RotatorModel{"hygain-ham4", "Hy-Gain HAM IV", fig(kRelay, "[HG1] 24 VAC capacitor motor"),
                 fig(kPot, "[HG3][HG4] 500 ohm pot"), fig(0, "[HG3] 360 deg"),
                 fig(360, "[HG3] 360 deg"), fig(0, "[HG1] azimuth"), kUnknown, kUnknown, kUnknown,
                 kUnknown, fig(1, "[HG1] brake solenoid"), kUnknown, kUnknown, kUnknown,
                 "Let the antenna coast to a stop before the brake engages [HG7]; the transformer "
                 "is rated for 10 % duty [HG1]."},
    RotatorModel{"hygain-t2x", "Hy-Gain Tailtwister T2X", fig(kRelay, "[HG9] AC motor"),
                 fig(kPot, "[HG9] 500 ohm pot"), kUnknown, kUnknown, fig(0, "[HG9] azimuth"),
                 kUnknown, kUnknown, kUnknown, kUnknown, fig(1, "[HG9] wedge brake solenoid"),
                 kUnknown, kUnknown, kUnknown,
                 "The wedge seats in 60 notches 6 deg apart [HG11]; a stuck brake needs a short "
                 "reverse first [HG12]."},
    RotatorModel{"hygain-cd45", "Hy-Gain CD-45 II", fig(kRelay, "[HG14] low-voltage AC motor"),
                 kUnknown, fig(0, "[HG14] 0-360"), fig(360, "[HG14] 0-360"),
                 fig(0, "[HG14] azimuth"), kUnknown, kUnknown, fig(6, "[HG14] about 1 rpm"),
                 kUnknown, fig(0, "[HG14] disc brake released by the motor itself"), kUnknown,
                 kUnknown, kUnknown, "End switches at both ends [HG14]."},
    RotatorModel{"spid-ras", "SPID RAS (Rot2Prog)", fig(kHBridge, "[S2] DC motor"), kUnknown,
                 fig(-180, "[S3][H1] -180..540"), fig(540, "[S3][H1] -180..540"),
                 fig(1, "[S2] az/el"), kUnknown, kUnknown, fig(6, "[S2] 360 deg in 60 s at 24 V"),
                 fig(6, "[S2] 360 deg in 60 s at 24 V"), fig(0, "[S2] worm drive, no brake"),
                 kUnknown, kUnknown, kUnknown,
                 "Pulse sensor (1, 2 or 4 pulses/deg [H1]): fit an MA3 encoder or a pot; no end "
                 "stops, software limits only [S3]. 3 deg/s at 12 V [S2]."},
    RotatorModel{"spid-big-ras", "SPID BIG-RAS", fig(kHBridge, "[S7] 12 V DC, ~1 kHz PWM"),
                 kUnknown, fig(-180, "[S4] -180..540"), fig(540, "[S4] -180..540"),
                 fig(1, "[S4] az/el"), kUnknown, kUnknown, kUnknown, kUnknown,
                 fig(0, "[S2] worm drive, no brake"), kUnknown, kUnknown, kUnknown,
                 "Hall pulse sensor, 0.0937 deg/pulse (/HR) [S4]: fit an MA3 encoder or a pot."},
    RotatorModel{"alfa-spx", "Alfa RAS / SPX", fig(kHBridge, "[S9] DC motor"), kUnknown,
                 fig(-180, "[S9] -180..540"), fig(540, "[S9] -180..540"), fig(1, "[S9] az/el"),
                 kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 "Pulse sensor via Rot2Prog [S9]: fit an MA3 encoder or a pot."},
    RotatorModel{"prosistel-d", "Prosistel PST-61D / 71D", kUnknown, kUnknown, fig(0, "[H3] 0-360"),
                 fig(360, "[H3] 0-360"), fig(0, "[H3] azimuth"), kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 "The D control box has a PWM soft-stop mode [H3]; the elevation unit is 0-90 deg "
                 "[H3]. Older PST641: pot [P1]."},
    RotatorModel{"create-rc5", "Create RC5-1 / RC5A-3", kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, "No figure found: self-commissioning measures the travel and speed."},
    RotatorModel{"other", "Other", kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown, kUnknown,
                 "Nothing is filled in: choose the drive and sensor, then self-commission."},
};

}  // namespace

std::span<const RotatorModel> rotator_models() {
  return kModels;
}

const RotatorModel* find_rotator_model(std::string_view id) {
  for (const RotatorModel& m : kModels)
    if (id == m.id) return &m;
  return nullptr;
}

std::size_t model_settings(const RotatorModel& m, ModelSetting* out, std::size_t capacity) {
  const bool el = m.has_el.known() && m.has_el.value != 0.0;
  const ModelSetting rows[kModelSettingCount] = {
      {Id::kAzDrive, &m.drive},
      {Id::kAzSensor, &m.sensor},
      {Id::kAzMinDeg, &m.az_min_deg},
      {Id::kAzMaxDeg, &m.az_max_deg},
      {Id::kElEnabled, &m.has_el},
      {Id::kAzSpeedDegS, &m.az_speed_deg_s},
      {Id::kAzHasBrake, &m.has_brake},
      {Id::kAzBrakeReleaseMs, &m.brake_release_ms},
      {Id::kAzBrakeEngageMs, &m.brake_engage_ms},
      {Id::kAzReverseDeadMs, &m.reverse_dead_ms},
      // Elevation rows last: an azimuth-only model has none.
      {Id::kElDrive, &m.drive},
      {Id::kElMinDeg, &m.el_min_deg},
      {Id::kElMaxDeg, &m.el_max_deg},
      {Id::kElSpeedDegS, &m.el_speed_deg_s},
  };
  constexpr std::size_t kAzRows = 10;
  const std::size_t n = el ? kModelSettingCount : kAzRows;
  std::size_t written = 0;
  for (std::size_t k = 0; k < n && written < capacity; ++k) out[written++] = rows[k];
  return written;
}

Rejection apply_rotator_model(const RotatorModel& model, Settings& s) {
  ModelSetting rows[kModelSettingCount];
  const std::size_t n = model_settings(model, rows, kModelSettingCount);
  Settings scratch = s;
  for (std::size_t k = 0; k < n; ++k) {
    if (!rows[k].figure->known()) continue;
    const Rejection r = scratch.set(rows[k].id, rows[k].figure->value);
    if (r.error != Error::kOk) return r;
  }
  const Rejection rule = scratch.check_consistency();
  if (rule.error != Error::kOk) return rule;
  for (std::size_t k = 0; k < n; ++k)
    if (rows[k].figure->known()) s.copy_value(rows[k].id, scratch);
  return {};
}

}  // namespace rotord::settings
