#pragma once
// libgpiod 1.6 (Debian 12's libgpiod-dev) behind the GpioChip boundary. The C
// API is used, not the C++ binding, because the binding reports errors with
// exceptions and this code reports them as start-up messages.
#include "gpio_line.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace rotord::linux_port {

class GpiodLine final : public GpioLine {
 public:
  explicit GpiodLine(gpiod_line* line) : line_(line) {}
  ~GpiodLine() override;
  GpiodLine(const GpiodLine&) = delete;
  GpiodLine& operator=(const GpiodLine&) = delete;

  bool set_active(bool active) override;
  int get_active() override;
  int event_fd() const override;
  std::size_t read_edges(LineEdge* out, std::size_t capacity) override;

 private:
  gpiod_line* line_;
};

class GpiodChip final : public GpioChip {
 public:
  GpiodChip(gpiod_chip* chip, std::string path);
  /// Lines requested from the chip must be destroyed first.
  ~GpiodChip() override;
  GpiodChip(const GpiodChip&) = delete;
  GpiodChip& operator=(const GpiodChip&) = delete;

  std::string describe() const override;
  std::unique_ptr<GpioLine> request(const LineRequest& request, std::string& error) override;

 private:
  gpiod_chip* chip_;
  std::string path_;
};

}  // namespace rotord::linux_port
