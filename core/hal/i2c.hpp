#pragma once
#include <cstddef>
#include <cstdint>

namespace rotord::hal {

/// An I2C bus master (7-bit addresses). Calls block for one transaction and
/// return false on a NAK or a timeout, never hang: a port bounds them (the
/// Pico W port uses the SDK's *_timeout_us calls).
class I2c {
 public:
  virtual ~I2c() = default;
  virtual bool write(std::uint8_t address, const std::uint8_t* data, std::size_t length) = 0;
  /// Writes `wlength` bytes (usually a register number), then reads `rlength`
  /// bytes after a repeated start.
  virtual bool write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                          std::uint8_t* rdata, std::size_t rlength) = 0;

  bool write_register(std::uint8_t address, std::uint8_t reg, std::uint8_t value) {
    const std::uint8_t bytes[2] = {reg, value};
    return write(address, bytes, 2);
  }
  bool read_registers(std::uint8_t address, std::uint8_t first_reg, std::uint8_t* out,
                      std::size_t count) {
    return write_read(address, &first_reg, 1, out, count);
  }
};

}  // namespace rotord::hal
