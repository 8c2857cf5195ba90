#include "gpiod_io.hpp"

#include <cstdio>
#include <optional>

#include "axis/axis_config.hpp"
#include "axis/sensor_registry.hpp"
#include "gpiod_wiring.hpp"
#include "log.hpp"
#include "sensors/magnetometer.hpp"
#include "sysfs_pwm.hpp"

namespace rotord::linux_port {
namespace {

using settings::Id;

const char* key(Id id) {
  return settings::def(id).key;
}

/// Requests lines by setting, collecting the first error.
class LineRequester {
 public:
  LineRequester(const settings::Settings& s, GpioChip& chip, std::string& error)
      : s_(s), chip_(chip), error_(error) {}

  bool failed() const { return !error_.empty(); }

  /// nullptr for an unwired (-1) line; `needed_by` makes that an error.
  std::unique_ptr<GpioLine> line(Id id, LineMode mode, const char* needed_by = nullptr) {
    if (failed()) return nullptr;
    const int offset = s_.i(id);
    if (offset < 0) {
      if (needed_by != nullptr) error_ = std::string(needed_by) + " needs " + key(id);
      return nullptr;
    }
    const bool is_output = mode == LineMode::kOutput;
    LineRequest r{key(id), offset, mode, false, LineBias::kAsIs};
    if (is_output) {
      r.active_low = s_.b(Id::kGpiodOutputsActiveLow);
    } else if (mode == LineMode::kInput) {
      r.active_low = s_.b(Id::kGpiodInputsActiveLow);
      r.bias = static_cast<LineBias>(s_.i(Id::kGpiodInputBias));
    }
    // The MA3 drives its line push-pull and its high time is the signal:
    // no inversion, no bias.
    return chip_.request(r, error_);
  }

  /// An edge line counted as pulses (the anemometer), with the inputs'
  /// polarity and bias (a reed contact to ground wants the pull-up).
  std::unique_ptr<GpiodPulseCounter> pulses(Id id) {
    if (failed() || s_.i(id) < 0) return nullptr;
    const LineRequest r{key(id), s_.i(id), LineMode::kBothEdges, s_.b(Id::kGpiodInputsActiveLow),
                        static_cast<LineBias>(s_.i(Id::kGpiodInputBias))};
    auto l = chip_.request(r, error_);
    return l ? std::make_unique<GpiodPulseCounter>(std::move(l)) : nullptr;
  }

  std::unique_ptr<GpiodSwitch> input(Id id, const char* needed_by = nullptr) {
    auto l = line(id, LineMode::kInput, needed_by);
    return l ? std::make_unique<GpiodSwitch>(std::move(l), key(id)) : nullptr;
  }

 private:
  const settings::Settings& s_;
  GpioChip& chip_;
  std::string& error_;
};

std::string choice(const settings::Settings& s, Id id) {
  return std::string(key(id)) + " = " + std::string(settings::choice_name(id, s.i(id)));
}

}  // namespace

void GpiodDriveSink::map(OutputChannel channel, std::unique_ptr<GpioLine> line) {
  lines_[static_cast<std::size_t>(channel)] = std::move(line);
}

void GpiodDriveSink::map(OutputChannel channel, std::unique_ptr<hal::PwmOut> pwm) {
  pwms_[static_cast<std::size_t>(channel)] = std::move(pwm);
}

void GpiodDriveSink::write(std::size_t channel, float value) {
  if (pwms_[channel]) {
    pwms_[channel]->set_duty(value);  // reports its own errors
    written_[channel] = value;
    return;
  }
  if (!lines_[channel]) return;
  if (lines_[channel]->set_active(value > 0.0f)) {
    written_[channel] = value > 0.0f ? 1.0f : 0.0f;
  } else if (!error_reported_) {
    error_reported_ = true;
    log::error("gpiod: writing an output line failed");
  }
}

void GpiodDriveSink::apply(const DriveOutputs& outputs) {
  for (std::size_t ch = 0; ch < kOutputChannelCount; ++ch) {
    const float value = pwms_[ch] ? outputs.value[ch] : (outputs.value[ch] > 0.0f ? 1.0f : 0.0f);
    if (value != written_[ch]) write(ch, value);
  }
}

void GpiodDriveSink::all_off() {
  for (std::size_t ch = 0; ch < kOutputChannelCount; ++ch) write(ch, 0.0f);
}

bool GpiodSwitch::active() {
  const int v = line_->get_active();
  if (v < 0) {
    if (!error_reported_) log::warn("gpiod: reading %s failed; it reads as not active", key_);
    error_reported_ = true;
    return false;
  }
  error_reported_ = false;
  return v == 1;
}

std::unique_ptr<GpiodRotator> GpiodRotator::open(const settings::Settings& s,
                                                 std::unique_ptr<GpioChip> chip,
                                                 const GpiodHost& host, std::string& error) {
  error.clear();
  std::unique_ptr<GpiodRotator> hw(new GpiodRotator(std::move(chip)));
  LineRequester req(s, *hw->chip_, error);
  hw->summary_ = "GPIO " + hw->chip_->describe();
  const auto analog = [&s](Id sensor) {
    const SensorInfo* type = find_sensor(s.i(sensor));
    return type != nullptr && type->input == SensorInput::kAnalog;
  };
  if (s.b(Id::kElEnabled) && analog(Id::kAzSensor) && analog(Id::kElSensor) &&
      s.i(Id::kIioAzDevice) == s.i(Id::kIioElDevice) &&
      s.i(Id::kIioAzChannel) == s.i(Id::kIioElChannel)) {
    error = "iio.az_channel and iio.el_channel both read channel " +
            std::to_string(s.i(Id::kIioAzChannel)) + " of IIO device " +
            std::to_string(s.i(Id::kIioAzDevice));
    return nullptr;
  }
  for (const AxisKeys* k : {&kAzKeys, &kElKeys}) {
    const bool el = k == &kElKeys;
    if (el && !s.b(Id::kElEnabled)) continue;
    AxisHw& a = hw->axis(el ? AxisId::kEl : AxisId::kAz);
    a.fitted = true;
    const auto drive = static_cast<DriveType>(s.i(k->drive));
    const std::string drive_text = choice(s, k->drive);
    // Outputs first, so they are driven inactive before anything can fail.
    std::string drive_where;
    if (drive == DriveType::kHBridge) {
      const int pwm_chip = s.i(Id::kPwmChip);
      if (pwm_chip < 0) {
        error = drive_text +
                " needs pwm.chip: H-bridges run on kernel PWM channels only (software PWM is not "
                "fit for a motor)";
        return nullptr;
      }
      for (const auto& [channel, id] : {std::pair{OutputChannel::kPwmCw, k->pwm_fwd},
                                        std::pair{OutputChannel::kPwmCcw, k->pwm_rev}}) {
        if (s.i(id) < 0) {
          error = drive_text + " needs " + key(id);
          return nullptr;
        }
        auto pwm = std::make_unique<SysfsPwm>();
        std::string why;
        if (!pwm->open(host.pwm_root, pwm_chip, s.i(id), s.i(Id::kPwmHz), why)) {
          error = std::string(key(id)) + " = " + std::to_string(s.i(id)) + ": " + why;
          return nullptr;
        }
        drive_where += (drive_where.empty() ? "PWM " : " and ") + pwm->path();
        a.drive.map(channel, std::unique_ptr<hal::PwmOut>(std::move(pwm)));
      }
    } else {
      a.drive.map(OutputChannel::kRelayCw,
                  req.line(k->relay_fwd, LineMode::kOutput, drive_text.c_str()));
      a.drive.map(OutputChannel::kRelayCcw,
                  req.line(k->relay_rev, LineMode::kOutput, drive_text.c_str()));
      drive_where =
          "lines " + std::to_string(s.i(k->relay_fwd)) + "/" + std::to_string(s.i(k->relay_rev));
    }
    if (drive == DriveType::kRelayTwoSpeed || drive == DriveType::kRelayVoltageSelect)
      a.drive.map(drive == DriveType::kRelayTwoSpeed ? OutputChannel::kSpeedFast
                                                     : OutputChannel::kVoltageFast,
                  req.line(k->speed, LineMode::kOutput, drive_text.c_str()));
    if (k->has_brake && s.b(*k->has_brake))
      a.drive.map(OutputChannel::kBrake,
                  req.line(*k->brake, LineMode::kOutput, key(*k->has_brake)));

    a.limit_cw = req.input(k->limit_cw);
    a.limit_ccw = req.input(k->limit_ccw);
    if (k->t1) a.t1 = req.input(*k->t1);
    if (k->t2) a.t2 = req.input(*k->t2);
    if (s.b(Id::kButtonsEnabled)) {
      a.button_fwd = req.input(k->button_fwd, key(Id::kButtonsEnabled));
      a.button_rev = req.input(k->button_rev, key(Id::kButtonsEnabled));
    }
    // The input the sensor type reads (its row), opened by this port's
    // factory for that input: a new type on one of these needs nothing here.
    const SensorInfo& type = *find_sensor(s.i(k->sensor));  // the table's range: a row
    const SensorInput input = type.input;
    const std::string sensor_text = choice(s, k->sensor);
    if (input == SensorInput::kPwm) {
      if (auto l = req.line(k->ma3, LineMode::kBothEdges, sensor_text.c_str()))
        a.ma3 = std::make_unique<GpiodMa3Input>(std::move(l), host.clock);
    }
    if (req.failed()) return nullptr;
    std::string sensor_where;
    if (input == SensorInput::kI2c) {
      if (!hw->open_magnetometer(s, host, sensor_where, error)) return nullptr;
    } else if (input == SensorInput::kAnalog) {
      const int device = s.i(k->iio_device);
      if (device < 0) {
        error = sensor_text + " needs " + key(k->iio_device);
        return nullptr;
      }
      a.pot = std::make_unique<IioAdc>();
      std::string why;
      if (!a.pot->open(host.iio_root, device, s.i(k->iio_channel), s.i(Id::kIioFullScaleCounts),
                       why)) {
        error = std::string(key(k->iio_device)) + ", " + key(k->iio_channel) + ": " + why;
        return nullptr;
      }
      sensor_where = std::string(type.name) + " " + a.pot->raw_path() + " (0.." +
                     std::to_string(a.pot->full_scale_counts()) + ")";
    } else {
      sensor_where = std::string(type.name) + " on line " + std::to_string(s.i(k->ma3));
    }
    hw->summary_ += std::string("; ") + k->name + ": " +
                    std::string(settings::choice_name(k->drive, s.i(k->drive))) + " drive on " +
                    drive_where + ", " + sensor_where;
  }
  hw->estop_ = req.input(Id::kGpiodEstop);
  const bool wind_pulses = s.i(Id::kWindSource) == 2;
  if (wind_pulses) hw->wind_ = req.pulses(Id::kGpiodWind);
  if (req.failed()) return nullptr;
  if (hw->wind_) {
    hw->summary_ += "; anemometer on line " + std::to_string(s.i(Id::kGpiodWind));
  } else if (wind_pulses) {
    hw->summary_ += "; wind.source = pulses, but gpiod.wind names no line: no wind readings";
  }
  if (hw->estop_)
    hw->summary_ += "; emergency stop on line " + std::to_string(s.i(Id::kGpiodEstop)) + " (" +
                    (s.b(Id::kEstopNormallyClosed) ? "normally-closed" : "normally-open") + ")";
  return hw;
}

bool GpiodRotator::open_magnetometer(const settings::Settings& s, const GpiodHost& host,
                                     std::string& where, std::string& error) {
  const int bus = s.i(Id::kI2cBus);
  if (bus < 0 || host.i2c_kernel == nullptr) {
    error = "az.sensor = mag needs i2c.bus";
    return false;
  }
  i2c_ = std::make_unique<I2cDev>(*host.i2c_kernel);
  std::string why;
  if (!i2c_->open(host.i2c_dev_root, bus, why)) {
    error = "i2c.bus = " + std::to_string(bus) + ": " + why;
    return false;
  }
  // Refused now rather than found as a sensor fault at the first tick, like
  // a missing ADC: the chip must answer and be the one mag.chip names.
  Magnetometer probe(*i2c_);
  const auto chip = static_cast<MagChip>(s.i(Id::kMagChip));
  probe.set_chip(chip);
  const bool qmc = chip == MagChip::kQmc5883l;
  char address[8];
  std::snprintf(address, sizeof address, "0x%02X",
                qmc ? Magnetometer::kQmcAddress : Magnetometer::kHmcAddress);
  const std::string chip_text = choice(s, Id::kMagChip);
  switch (probe.begin()) {
    case Magnetometer::Status::kNoAnswer:
      error = chip_text + ": nothing answers at " + address + " on " + i2c_->path() +
              " (wiring, power, pull-ups? `i2cdetect -y " + std::to_string(bus) + "` lists it)";
      return false;
    case Magnetometer::Status::kWrongChip:
      error = chip_text + ": the chip at " + address + " on " + i2c_->path() +
              " does not identify as one (is mag.chip right?)";
      return false;
    default:
      break;
  }
  where = "magnetometer " + std::string(qmc ? "QMC5883L" : "HMC5883L") + " at " + address + " on " +
          i2c_->path();
  return true;
}

GpiodRotator::~GpiodRotator() {
  all_off();
}

AxisIo GpiodRotator::io(AxisId id) {
  AxisHw& a = axis(id);
  AxisIo io;
  if (!a.fitted) return io;
  io.drive = &a.drive;
  io.pot = a.pot.get();
  io.ma3 = a.ma3.get();
  io.limit_cw = a.limit_cw.get();
  io.limit_ccw = a.limit_ccw.get();
  io.t1 = a.t1.get();
  io.t2 = a.t2.get();
  io.button_fwd = a.button_fwd.get();
  io.button_rev = a.button_rev.get();
  if (id == AxisId::kAz) io.i2c = i2c_.get();
  return io;
}

void GpiodRotator::watch(asio::io_context& io) {
  for (AxisHw* a : {&az_, &el_})
    if (a->ma3) a->ma3->watch(io);
  if (wind_) wind_->watch(io);
}

void GpiodRotator::sample() {
  for (AxisHw* a : {&az_, &el_}) {
    if (!a->pot) continue;
    const bool ok = a->pot->sample();
    if (!ok && !a->pot_error_reported) log::warn("%s", a->pot->last_error().c_str());
    a->pot_error_reported = !ok;
  }
}

void GpiodRotator::all_off() {
  az_.drive.all_off();
  el_.drive.all_off();
}

}  // namespace rotord::linux_port
