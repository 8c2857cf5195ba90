#include "sim/profiles.hpp"

#include <array>

#include "sim/adc_scale.hpp"
#include "sim/sensor_overrides.hpp"

namespace rotord::sim {

namespace {

// Where the hardware sits relative to the working range: limit switches close
// 1 deg beyond the range ends, the mechanical stops are 3 deg beyond.
constexpr double kLimitSwitchMarginDeg = 1.0;
constexpr double kEndStopMarginDeg = 3.0;

// ADC noise: ENOB ~8.7 on the RP2040 is ~2.8 LSB RMS.
constexpr double kPotSigma_v = 2.8 * kAdcLsb_v;

// G-5500 pot outputs 0.05..4.11 V over 450 deg, divided to ~3.0 V full scale.
constexpr PotMapping kDividedPot{.v_at_min_v = 0.05, .v_at_max_v = 3.0, .sigma_v = kPotSigma_v};

constexpr AxisProfile make_axis(AxisPlantParams plant, double min_deg, double max_deg,
                                SensorType sensor) {
  AxisProfile a;
  plant.stop_min_deg = min_deg - kEndStopMarginDeg;
  plant.stop_max_deg = max_deg + kEndStopMarginDeg;
  a.plant = plant;
  a.min_deg = min_deg;
  a.max_deg = max_deg;
  a.sensor = sensor;
  a.pot = kDividedPot;
  a.limit_cw_deg = max_deg + kLimitSwitchMarginDeg;
  a.limit_ccw_deg = min_deg - kLimitSwitchMarginDeg;
  return a;
}

// An azimuth range wider than one turn has overlap zones, each with a
// threshold sensor.
constexpr AxisProfile with_overlap_sensors(AxisProfile a) {
  a.has_t1 = a.max_deg > a.t1_above_deg;
  a.has_t2 = a.min_deg < a.t2_below_deg;
  return a;
}

// ---- the rotator presets ----

// G5500_AZ_LIKE: 6 deg/s, tau_m 0.20 s, tau_c 0.15 s, backlash 1.0, relay 10 ms.
constexpr AxisPlantParams kG5500AzPlant{.v_max_deg_s = 6.0,
                                        .tau_m_s = 0.20,
                                        .tau_c_s = 0.15,
                                        .backlash_deg = 1.0,
                                        .relay_delay_s = 0.010,
                                        .drive = DriveKind::kRelay};
// G5500_EL_LIKE: 2.7 deg/s, tau_m 0.20 s, tau_c 0.10 s, backlash 1.5, relay 10 ms.
constexpr AxisPlantParams kG5500ElPlant{.v_max_deg_s = 2.7,
                                        .tau_m_s = 0.20,
                                        .tau_c_s = 0.10,
                                        .backlash_deg = 1.5,
                                        .relay_delay_s = 0.010,
                                        .drive = DriveKind::kRelay};
// SPID_RAS_LIKE_24V: 6 deg/s, tau_m 0.10 s, tau_c 0.05 s (worm gear, little
// coast), backlash 0.3, no relay, PWM dead band 0.30.
constexpr AxisPlantParams kSpidPlant{.v_max_deg_s = 6.0,
                                     .tau_m_s = 0.10,
                                     .tau_c_s = 0.05,
                                     .backlash_deg = 0.3,
                                     .relay_delay_s = 0.0,
                                     .pwm_dead_band = 0.30,
                                     .drive = DriveKind::kHBridge};
// Ham IV (bell rotator): ~1 rpm, heavier bell so a slower start [est], coast
// 0.15 s, spur train backlash 1.0 [est], wedge brake that stops a coasting
// bell within ~0.3 deg [est].
constexpr AxisPlantParams kHam4Plant{.v_max_deg_s = 6.0,
                                     .tau_m_s = 0.25,
                                     .tau_c_s = 0.15,
                                     .backlash_deg = 1.0,
                                     .relay_delay_s = 0.010,
                                     .drive = DriveKind::kRelay,
                                     .has_brake = true,
                                     .brake_decel_deg_s2 = 60.0};

constexpr AxisProfile kG5500Az =
    with_overlap_sensors(make_axis(kG5500AzPlant, 0, 450, SensorType::kPot));
constexpr AxisProfile kG5500El = make_axis(kG5500ElPlant, 0, 180, SensorType::kPot);
constexpr AxisProfile kHam4Az =
    with_overlap_sensors(make_axis(kHam4Plant, 0, 360, SensorType::kPot));
constexpr AxisProfile kSpidAz =
    with_overlap_sensors(make_axis(kSpidPlant, -180, 540, SensorType::kMa3));
constexpr AxisProfile kSpidEl = make_axis(kSpidPlant, 0, 180, SensorType::kMa3);

// ---- settings overrides, derived from the axis profiles above ----

struct AxisKeys {
  const char* min_deg;
  const char* max_deg;
  const char* drive;
  const char* has_brake;  // nullptr: the axis has no such setting
  SensorKeys sensor;
};

constexpr AxisKeys kAzKeys{"az.min_deg", "az.max_deg", "az.drive", "az.has_brake", kAzSensorKeys};
constexpr AxisKeys kElKeys{"el.min_deg", "el.max_deg", "el.drive", nullptr, kElSensorKeys};

constexpr std::size_t kMaxOverrides = 24;

struct OverrideList {
  std::array<SettingOverride, kMaxOverrides> items{};
  std::size_t count = 0;

  constexpr void add(const char* key, double value) { items[count++] = {key, value}; }
  constexpr void add_axis(const AxisKeys& keys, const AxisProfile& a) {
    add(keys.min_deg, a.min_deg);
    add(keys.max_deg, a.max_deg);
    add(keys.drive, static_cast<double>(a.plant.drive));
    if (keys.has_brake != nullptr) add(keys.has_brake, a.plant.has_brake ? 1.0 : 0.0);
    add_sensor_overrides(a, keys.sensor, items.data(), count);
  }
  constexpr std::span<const SettingOverride> view() const { return {items.data(), count}; }
};

constexpr OverrideList make_overrides(bool has_el, const AxisProfile& az, const AxisProfile& el) {
  OverrideList list;
  list.add("el.enabled", has_el ? 1.0 : 0.0);
  list.add_axis(kAzKeys, az);
  if (has_el) list.add_axis(kElKeys, el);
  return list;
}

constexpr OverrideList kG5500Overrides = make_overrides(true, kG5500Az, kG5500El);
constexpr OverrideList kHam4Overrides = make_overrides(false, kHam4Az, AxisProfile{});
constexpr OverrideList kSpidOverrides = make_overrides(true, kSpidAz, kSpidEl);

constexpr Profile kG5500{
    "g5500",  "Yaesu G-5500-like az/el: relays only, pots, az 0..450 (overlap), el 0..180",
    true,     kG5500Az,
    kG5500El, kG5500Overrides.view()};
constexpr Profile kHam4{
    "ham4",        "Hy-Gain Ham IV-like az: relays plus brake solenoid, pot, 0..360",
    false,         kHam4Az,
    AxisProfile{}, kHam4Overrides.view()};
constexpr Profile kSpid{
    "spid",  "SPID RAS-like 24 V az/el: H-bridge PWM, MA3 12-bit encoders, az -180..540",
    true,    kSpidAz,
    kSpidEl, kSpidOverrides.view()};

constexpr std::array<const Profile*, 3> kProfiles{&kG5500, &kHam4, &kSpid};

}  // namespace

const Profile* find_profile(std::string_view name) {
  for (const Profile* p : kProfiles) {
    if (name == p->name) return p;
  }
  return nullptr;
}

std::span<const Profile* const> all_profiles() {
  return kProfiles;
}

}  // namespace rotord::sim
