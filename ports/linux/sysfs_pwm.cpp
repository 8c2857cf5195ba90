#include "sysfs_pwm.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

#include "host_path.hpp"
#include "log.hpp"

namespace rotord::linux_port {
namespace {

bool exists(const std::string& path) {
  return ::access(path.c_str(), F_OK) == 0;
}

}  // namespace

std::string pwm_root() {
  return host_path("ROTORD_PWM_ROOT", "/sys/class/pwm");
}

bool SysfsPwm::write_file(const std::string& name, const std::string& value,
                          std::string& error) const {
  const std::string path = dir_.empty() || name == "export" || name == "unexport"
                               ? chip_dir_ + "/" + name
                               : dir_ + "/" + name;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  const bool ok =
      fd >= 0 && ::write(fd, value.data(), value.size()) == static_cast<ssize_t>(value.size());
  const int err = errno;
  if (fd >= 0) ::close(fd);
  if (!ok) error = "cannot write " + value + " to " + path + ": " + std::strerror(err);
  return ok;
}

bool SysfsPwm::open(const std::string& root, int chip, int channel, int hz, std::string& error) {
  chip_dir_ = root + "/pwmchip" + std::to_string(chip);
  channel_ = channel;
  if (!exists(chip_dir_)) {
    error = "no PWM chip " + chip_dir_ + " (is a PWM overlay loaded? see docs/gpiod.md)";
    return false;
  }
  const std::string dir = chip_dir_ + "/pwm" + std::to_string(channel);
  if (!exists(dir)) {
    if (!write_file("export", std::to_string(channel), error)) return false;
    exported_ = true;
    // udev gives the new files their group a moment after they appear.
    for (int k = 0; k < 100 && ::access((dir + "/duty_cycle").c_str(), W_OK) != 0; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  dir_ = dir;
  period_ns_ = 1'000'000'000ull / static_cast<std::uint64_t>(hz);
  // duty_cycle may never exceed period: zero it first, whatever was set.
  write_file("duty_cycle", "0", error);
  if (!write_file("period", std::to_string(period_ns_), error) ||
      !write_file("duty_cycle", "0", error) || !write_file("enable", "1", error))
    return false;
  error.clear();
  duty_fd_ = ::open((dir_ + "/duty_cycle").c_str(), O_WRONLY | O_CLOEXEC);
  if (duty_fd_ < 0) {
    error = "cannot open " + dir_ + "/duty_cycle: " + std::strerror(errno);
    return false;
  }
  duty_ns_ = 0;
  return true;
}

void SysfsPwm::set_duty(float duty) {
  if (duty_fd_ < 0) return;
  if (duty < 0.0f) duty = 0.0f;
  if (duty > 1.0f) duty = 1.0f;
  const auto ns =
      static_cast<std::uint64_t>(static_cast<double>(duty) * static_cast<double>(period_ns_) + 0.5);
  if (ns == duty_ns_) return;
  const std::string text = std::to_string(ns);
  if (::pwrite(duty_fd_, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size())) {
    duty_ns_ = ns;
    error_reported_ = false;
  } else if (!error_reported_) {
    error_reported_ = true;
    log::warn("writing %s/duty_cycle failed: %s", dir_.c_str(), std::strerror(errno));
  }
}

SysfsPwm::~SysfsPwm() {
  if (dir_.empty()) return;
  set_duty(0.0f);
  if (duty_fd_ >= 0) ::close(duty_fd_);
  std::string ignored;
  write_file("enable", "0", ignored);
  if (exported_) {
    dir_.clear();
    write_file("unexport", std::to_string(channel_), ignored);
  }
}

}  // namespace rotord::linux_port
