// A firmware-shaped image for measuring the core: a Controller with a WRC
// session on hardware that is only volatile variables, in the poll loop a
// Pico W port runs. Built twice: as is, and with ROTORD_SIZE_BASELINE (same
// startup and loop, no core); size-report.cmake subtracts the two. Never run.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#ifndef ROTORD_SIZE_BASELINE
#include "axis/axis_io.hpp"
#include "command/buttons.hpp"
#include "protocol/wrc_session.hpp"
#include "rotator/controller.hpp"
#include "settings/settings.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/places.hpp"
#endif

extern "C" {
extern std::uint32_t __bss_start__[];
extern std::uint32_t __bss_end__[];
extern std::uint32_t __stack_top[];
void __libc_init_array();
[[noreturn]] void rotord_reset_handler();
}

namespace {

// Stand-ins for peripheral registers: volatile, so that the compiler keeps
// every access and cannot fold the core away.
volatile std::uint32_t g_millis;
volatile std::uint16_t g_adc;
volatile std::uint32_t g_pins;
volatile std::uint32_t g_pwm_high_us;
volatile float g_duty[8];
volatile char g_rx;
volatile char g_tx;

#ifndef ROTORD_SIZE_BASELINE
using namespace rotord;

class Adc final : public hal::AnalogIn {
 public:
  std::uint16_t read_counts() override { return g_adc; }
  std::uint16_t full_scale_counts() const override { return 4095; }
  float reference_v() const override { return 3.3f; }
};

class Pin final : public hal::DigitalIn {
 public:
  explicit Pin(unsigned bit) : bit_(bit) {}
  bool active() override { return (g_pins >> bit_) & 1u; }

 private:
  unsigned bit_;
};

class Pwm final : public hal::PwmIn {
 public:
  hal::PwmPeriod read() override { return {g_pwm_high_us, 1024 - g_pwm_high_us, true}; }
};

class Drive final : public DriveSink {
 public:
  void apply(const DriveOutputs& outputs) override {
    for (std::size_t i = 0; i < kOutputChannelCount && i < 8; ++i) g_duty[i] = outputs.value[i];
  }
};

class Uart final : public protocol::ByteSink {
 public:
  void write(std::string_view bytes) override {
    for (char c : bytes) g_tx = c;
  }
};

// Namespace-scope objects, as a port's composition root would have them.
Adc g_az_pot;
Pwm g_el_ma3;
Pin g_az_cw{0}, g_az_ccw{1}, g_el_up{2}, g_el_down{3};
Drive g_az_drive, g_el_drive;
Uart g_uart;
settings::Settings g_settings;
Controller g_controller{
    g_settings, AxisIo{&g_az_pot, nullptr, &g_az_cw, &g_az_ccw, nullptr, nullptr, &g_az_drive},
    AxisIo{nullptr, &g_el_ma3, &g_el_up, &g_el_down, nullptr, nullptr, &g_el_drive}};
// The manual buttons' front end, polled before each tick as the Pico W
// port does (no buttons wired here, as before the command layer had them).
command::Buttons g_buttons{g_controller, AxisIo{}, AxisIo{}};
protocol::WrcSession g_wrc{g_controller, ROTORD_VERSION};
// Tracking: a target from TLE lines as if uploaded, its look angles every
// loop, a pass search a few evaluations per loop, a bearing to a locator.
volatile char g_tle_lines[2][70];
tracking::SkyTarget g_target;
tracking::PassFinder g_passes;
#endif

}  // namespace

namespace {

[[noreturn]] void firmware_main() {
#ifndef ROTORD_SIZE_BASELINE
  g_controller.begin(g_millis);
  char lines[2][70];
  for (int l = 0; l < 2; ++l)
    for (int i = 0; i < 70; ++i) lines[l][i] = g_tle_lines[l][i];
  tracking::Tle tle;
  if (tracking::parse_tle(std::string_view(lines[0], 69), std::string_view(lines[1], 69), tle).ok())
    (void)g_target.set_satellite(tle);
  else
    g_target.set_body(g_rx == 's' ? tracking::Body::kSun : tracking::Body::kMoon);
  const tracking::Observer observer(tracking::Geodetic{g_settings.get(settings::Id::kStationLatDeg),
                                                       g_settings.get(settings::Id::kStationLonDeg),
                                                       g_settings.get(settings::Id::kStationAltM)});
  g_passes.start(g_target, observer, g_millis, g_millis + 86'400'000, 0.0);
  tracking::LatLon place;
  if (tracking::maidenhead_centre(std::string_view(lines[0], 6), place))
    g_duty[7] = static_cast<float>(
        tracking::great_circle({0.0, 0.0}, place, tracking::Path::kLong).azimuth_deg);
#endif
  for (;;) {
    const char c = g_rx;
#ifndef ROTORD_SIZE_BASELINE
    g_wrc.receive(std::string_view(&c, 1), g_uart);
    g_buttons.poll(g_millis);
    g_controller.tick(g_millis);
    g_wrc.poll(g_millis, g_uart);
    tracking::LookAngles look;
    if (g_target.look(g_millis, observer, look) == tracking::Sgp4Error::kOk)
      g_duty[6] = static_cast<float>(look.az_deg);
    if (g_passes.step(2) == tracking::PassFinder::Status::kFound)
      g_duty[5] = static_cast<float>(g_passes.pass().max_el_deg);
#else
    g_tx = c;
#endif
  }
}

}  // namespace

[[noreturn]] void rotord_reset_handler() {
  std::memset(__bss_start__, 0,
              static_cast<std::size_t>(reinterpret_cast<char*>(__bss_end__) -
                                       reinterpret_cast<char*>(__bss_start__)));
  __libc_init_array();
  firmware_main();
}

namespace {
using Handler = void (*)();
}

// The smallest vector table a Cortex-M boots from: initial stack, reset.
__attribute__((section(".vectors"), used))
const Handler g_vectors[2] = {reinterpret_cast<Handler>(__stack_top), rotord_reset_handler};
