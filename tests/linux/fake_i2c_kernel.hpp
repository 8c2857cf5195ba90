#pragma once
// The kernel side of /dev/i2c-N in tests: I2C_RDWR transactions are decoded
// the way the i2c core does and handed to a register model of a chip (the
// simulator's QMC5883L), and every transaction is recorded.
#include <cerrno>
#include <cstdint>
#include <vector>

#include "hal/i2c.hpp"
#include "i2c_dev.hpp"

namespace rotord::testing {

class FakeI2cKernel final : public linux_port::I2cKernel {
 public:
  struct Message {
    std::uint16_t address;
    bool read;
    std::size_t length;
  };

  hal::I2c* device = nullptr;  ///< nullptr: nothing on the bus (every NAK)
  unsigned long funcs = I2C_FUNC_I2C | I2C_FUNC_SMBUS_EMUL;
  std::vector<std::vector<Message>> transactions;

  int functionality(int /*fd*/, unsigned long& out) override {
    out = funcs;
    return 0;
  }

  int transfer(int /*fd*/, i2c_rdwr_ioctl_data& data) override {
    std::vector<Message> t;
    for (unsigned n = 0; n < data.nmsgs; ++n) {
      const i2c_msg& m = data.msgs[n];
      t.push_back({m.addr, (m.flags & I2C_M_RD) != 0, m.len});
    }
    transactions.push_back(t);
    bool ok = device != nullptr;
    const i2c_msg* m = data.msgs;
    if (ok && data.nmsgs == 1 && (m[0].flags & I2C_M_RD) == 0) {
      ok = device->write(static_cast<std::uint8_t>(m[0].addr), m[0].buf, m[0].len);
    } else if (ok && data.nmsgs == 2 && (m[0].flags & I2C_M_RD) == 0 &&
               (m[1].flags & I2C_M_RD) != 0 && m[0].addr == m[1].addr) {
      ok = device->write_read(static_cast<std::uint8_t>(m[0].addr), m[0].buf, m[0].len, m[1].buf,
                              m[1].len);
    } else {
      ok = false;
    }
    if (!ok) {
      errno = ENXIO;  // no acknowledge from the address
      return -1;
    }
    return static_cast<int>(data.nmsgs);
  }
};

}  // namespace rotord::testing
