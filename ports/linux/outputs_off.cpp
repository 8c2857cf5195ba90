#include "outputs_off.hpp"

#include <vector>

#include "axis/axis_config.hpp"
#include "gpiod_wiring.hpp"
#include "log.hpp"
#include "print_config.hpp"
#include "sysfs_pwm.hpp"

namespace rotord::linux_port {
namespace {

using settings::Id;

const char* key(Id id) {
  return settings::def(id).key;
}

void append(std::string& list, const std::string& item, const char* separator) {
  if (!list.empty()) list += separator;
  list += item;
}

}  // namespace

OutputsOffResult drive_outputs_off(const settings::Settings& s, const OpenChip& open_chip,
                                   const std::string& pwm_root) {
  OutputsOffResult result;
  std::vector<Id> lines;
  std::vector<Id> channels;
  for (const AxisKeys* k : {&kAzKeys, &kElKeys}) {
    if (k == &kElKeys && !s.b(Id::kElEnabled)) continue;
    const auto drive = static_cast<DriveType>(s.i(k->drive));
    if (drive == DriveType::kHBridge) {
      channels.push_back(k->pwm_fwd);
      channels.push_back(k->pwm_rev);
    } else {
      lines.push_back(k->relay_fwd);
      lines.push_back(k->relay_rev);
    }
    if (drive == DriveType::kRelayTwoSpeed || drive == DriveType::kRelayVoltageSelect)
      lines.push_back(k->speed);
    if (k->has_brake && s.b(*k->has_brake)) lines.push_back(*k->brake);
  }
  std::erase_if(lines, [&s](Id id) { return s.i(id) < 0; });  // not wired

  if (!lines.empty()) {
    std::string error;
    std::unique_ptr<GpioChip> chip = open_chip(error);
    if (!chip) append(result.errors, error, "; ");
    for (const Id id : lines) {
      if (!chip) break;
      const LineRequest request{key(id), s.i(id), LineMode::kOutput,
                                s.b(Id::kGpiodOutputsActiveLow), LineBias::kAsIs};
      std::unique_ptr<GpioLine> line = chip->request(request, error);
      // Requested inactive already; written once more in case the chip's
      // driver kept the old level until the first write.
      if (!line || !line->set_active(false)) {
        append(result.errors, line ? std::string(key(id)) + ": writing the line failed" : error,
               "; ");
        continue;
      }
      line.reset();  // released: the line keeps the inactive level
      ++result.lines_off;
      append(result.done, std::string(key(id)) + " line " + std::to_string(s.i(id)), ", ");
    }
  }
  for (const Id id : channels) {
    const int chip = s.i(Id::kPwmChip);
    if (chip < 0 || s.i(id) < 0) {
      // The daemon refuses to start like this, so nothing was driven.
      continue;
    }
    std::string error;
    {
      SysfsPwm pwm;  // open: duty 0; destroyed: duty 0 and disabled
      if (!pwm.open(pwm_root, chip, s.i(id), s.i(Id::kPwmHz), error)) {
        append(result.errors, std::string(key(id)) + " = " + std::to_string(s.i(id)) + ": " + error,
               "; ");
        continue;
      }
    }
    ++result.channels_off;
    append(result.done,
           std::string(key(id)) + " PWM " + std::to_string(chip) + "/" + std::to_string(s.i(id)),
           ", ");
  }
  return result;
}

int run_outputs_off(const Options& options) {
  if (options.hw != "gpiod") {
    log::info("--outputs-off: nothing to drive under --hw %s", options.hw.c_str());
    return 0;
  }
  // Heap is fine: a one-shot command, not the daemon.
  auto base = std::make_unique<settings::Settings>();
  auto s = std::make_unique<settings::Settings>();
  FileStorage storage(settings_path(options));
  std::string why;
  const web::LoadOutcome r = load_file_settings(storage, nullptr, *base, *s, why);
  if (!why.empty()) {
    log::error("--outputs-off: settings file %s %s", storage.path().c_str(), why.c_str());
    return 2;
  }
  if (r.status == web::LoadOutcome::kCorrupt) {
    // The daemon ran on the defaults then: those are its lines.
    log::warn("--outputs-off: settings file %s is invalid; driving the default lines off",
              storage.path().c_str());
  }
  const OutputsOffResult result = drive_outputs_off(
      *s,
      [&s](std::string& error) { return open_gpiod_chip(s->i(settings::Id::kGpiodChip), error); },
      pwm_root());
  if (!result.done.empty()) log::info("outputs off: %s", result.done.c_str());
  if (result.ok()) {
    if (result.done.empty()) log::info("--outputs-off: no output is wired");
    return 0;
  }
  log::error("--outputs-off: %s", result.errors.c_str());
  return 1;
}

}  // namespace rotord::linux_port
