#include "gpiod_chip.hpp"

#include <gpiod.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>

namespace rotord::linux_port {
namespace {

constexpr const char kConsumer[] = "rotord";

int request_type(LineMode mode) {
  switch (mode) {
    case LineMode::kOutput:
      return GPIOD_LINE_REQUEST_DIRECTION_OUTPUT;
    case LineMode::kInput:
      return GPIOD_LINE_REQUEST_DIRECTION_INPUT;
    case LineMode::kBothEdges:
      return GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES;
  }
  return GPIOD_LINE_REQUEST_DIRECTION_INPUT;
}

int request_flags(const LineRequest& r) {
  int flags = r.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (r.mode == LineMode::kOutput) return flags;
  switch (r.bias) {
    case LineBias::kPullUp:
      return flags | GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
    case LineBias::kPullDown:
      return flags | GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
    case LineBias::kDisable:
      return flags | GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
    case LineBias::kAsIs:
      break;
  }
  return flags;
}

}  // namespace

GpiodLine::~GpiodLine() {
  gpiod_line_release(line_);
}

bool GpiodLine::set_active(bool active) {
  return gpiod_line_set_value(line_, active ? 1 : 0) == 0;
}

int GpiodLine::get_active() {
  return gpiod_line_get_value(line_);
}

int GpiodLine::event_fd() const {
  return gpiod_line_event_get_fd(line_);
}

std::size_t GpiodLine::read_edges(LineEdge* out, std::size_t capacity) {
  std::size_t n = 0;
  gpiod_line_event events[16];
  while (n < capacity) {
    const timespec no_wait{0, 0};
    if (gpiod_line_event_wait(line_, &no_wait) != 1) break;
    const auto want = static_cast<unsigned>(std::min(capacity - n, std::size(events)));
    const int got = gpiod_line_event_read_multiple(line_, events, want);
    if (got <= 0) break;
    for (int k = 0; k < got; ++k) {
      const timespec& ts = events[k].ts;
      out[n++] = {events[k].event_type == GPIOD_LINE_EVENT_RISING_EDGE,
                  static_cast<std::uint64_t>(ts.tv_sec) * 1'000'000'000u +
                      static_cast<std::uint64_t>(ts.tv_nsec)};
    }
  }
  return n;
}

GpiodChip::GpiodChip(gpiod_chip* chip, std::string path) : chip_(chip), path_(std::move(path)) {}

GpiodChip::~GpiodChip() {
  gpiod_chip_close(chip_);
}

std::string GpiodChip::describe() const {
  const char* label = gpiod_chip_label(chip_);
  return path_ + " (" + (label != nullptr ? label : "?") + ")";
}

std::unique_ptr<GpioLine> GpiodChip::request(const LineRequest& r, std::string& error) {
  const std::string where =
      std::string(r.key) + " = " + std::to_string(r.offset) + ": line " + std::to_string(r.offset);
  const unsigned lines = gpiod_chip_num_lines(chip_);
  if (r.offset < 0 || static_cast<unsigned>(r.offset) >= lines) {
    error = where + " does not exist: " + describe() + " has lines 0 to " +
            std::to_string(lines == 0 ? 0 : lines - 1);
    return nullptr;
  }
  gpiod_line* line = gpiod_chip_get_line(chip_, static_cast<unsigned>(r.offset));
  if (line == nullptr) {
    error = where + " of " + describe() + ": " + std::strerror(errno);
    return nullptr;
  }
  const gpiod_line_request_config config{kConsumer, request_type(r.mode), request_flags(r)};
  if (gpiod_line_request(line, &config, 0) != 0) {
    const int err = errno;
    error = where + " of " + describe();
    if (err == EBUSY) {
      gpiod_line_update(line);
      const char* user = gpiod_line_consumer(line);
      error += " is busy (used by " + std::string(user != nullptr ? user : "another program") +
               "); free it or choose another line";
    } else {
      error += " cannot be requested: " + std::string(std::strerror(err));
      if (err == EINVAL && r.mode != LineMode::kOutput)
        error += " (bias flags need Linux 5.5 or later; try gpiod.input_bias = as_is)";
    }
    return nullptr;
  }
  return std::make_unique<GpiodLine>(line);
}

std::unique_ptr<GpioChip> open_gpiod_chip(int number, std::string& error) {
  const std::string path = "/dev/gpiochip" + std::to_string(number);
  gpiod_chip* chip = gpiod_chip_open_by_number(static_cast<unsigned>(number));
  if (chip == nullptr) {
    const int err = errno;
    error = "cannot open GPIO chip " + path + " (gpiod.chip = " + std::to_string(number) +
            "): " + std::strerror(err);
    if (err == ENOENT) error += "; `gpiodetect` lists the chips of this machine";
    if (err == EACCES) error += "; add the user to the gpio group";
    return nullptr;
  }
  return std::make_unique<GpiodChip>(chip, path);
}

}  // namespace rotord::linux_port
