#pragma once
// A potentiometer on a Linux IIO ADC, read through sysfs:
//   <root>/iio:deviceN/in_voltageM_raw    one conversion per read
//   <root>/iio:deviceN/in_voltageM_scale  mV per count (or in_voltage_scale)
//   <root>/iio:deviceN/name               the driver's chip name
//   <root>/iio:deviceN/scan_elements/in_voltageM_type   sign and bits
// The kernel drivers do the bus work (ti-ads1015 for an ADS1015/ADS1115 on
// I2C, mcp320x for an MCP3008/MCP3208 on SPI), so rotord needs no I2C or SPI
// code of its own for them.
#include <cstdint>
#include <string>

#include "hal/analog_in.hpp"

namespace rotord::linux_port {

/// The sysfs root of IIO devices; ROTORD_IIO_ROOT replaces it (for tests,
/// which point it at a fake tree in a temporary directory).
std::string iio_root();

/// Highest code of a known IIO ADC by its driver name, or 0 when the name
/// is unknown (or ambiguous, as ti-ads1015's "ads1015" for every ADS1x15).
int iio_full_scale_for(const std::string& name);
/// Highest single-ended code from a scan element type ("le:s16/16>>0" is an
/// ADS1115: 32767), or 0 when it cannot be parsed.
int iio_full_scale_from_type(const std::string& type);

/// One channel of an IIO ADC as the core's hal::AnalogIn. A conversion costs
/// a bus transfer (an ADS1115 at its default 128 samples/s blocks a read for
/// up to 8 ms), so the port calls sample() once per control tick and every
/// read_counts() of that tick returns the same code: the pot sensor's
/// oversampling then sees one value, and the ADC's own filter does that
/// job. A failed read gives 0 counts, which the core reports as a sensor at
/// its rail (open wiper).
class IioAdc final : public hal::AnalogIn {
 public:
  IioAdc() = default;
  ~IioAdc() override;
  IioAdc(const IioAdc&) = delete;
  IioAdc& operator=(const IioAdc&) = delete;

  /// Opens the channel and reads its scale. `full_scale_counts` 0 takes the
  /// full scale from scan_elements/in_voltageM_type, else the driver's name. False with `error`
  /// naming the file that is missing or unreadable.
  bool open(const std::string& root, int device, int channel, int full_scale_counts,
            std::string& error);
  /// Reads one conversion; false (and 0 counts) on an error.
  bool sample();

  std::uint16_t read_counts() override { return counts_; }
  std::uint16_t full_scale_counts() const override { return full_scale_; }
  float reference_v() const override { return reference_v_; }
  const std::string& raw_path() const { return raw_path_; }
  /// The error of the last failed sample(), empty after a good one.
  const std::string& last_error() const { return last_error_; }

 private:
  int fd_ = -1;
  std::string raw_path_;
  std::uint16_t counts_ = 0;
  std::uint16_t full_scale_ = 0;
  float reference_v_ = 0.0f;
  std::string last_error_;
};

}  // namespace rotord::linux_port
