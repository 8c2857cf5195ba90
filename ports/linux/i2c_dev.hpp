#pragma once
// An I2C adapter through the kernel's i2c-dev interface (/dev/i2c-N), for the
// magnetometer under `rotord --hw gpiod`. Each transaction is one I2C_RDWR
// ioctl: a register read is the register number written, then the bytes
// read after a repeated start, in one call, as the QMC5883L and HMC5883L
// expect and as no other process on the bus can split.
#include <linux/i2c-dev.h>
#include <linux/i2c.h>

#include <string>

#include "hal/i2c.hpp"

namespace rotord::linux_port {

/// The kernel's side of an i2c-dev file: the two ioctls rotord uses. Tests
/// put a register model of a chip behind it (the hardware boundary).
class I2cKernel {
 public:
  virtual ~I2cKernel() = default;
  /// I2C_FUNCS: what the adapter can do; -1 with errno on an error.
  virtual int functionality(int fd, unsigned long& funcs) = 0;
  /// I2C_RDWR: the messages as one transaction; -1 with errno on an error
  /// (a NAK is EREMOTEIO or ENXIO, a stuck bus ETIMEDOUT).
  virtual int transfer(int fd, i2c_rdwr_ioctl_data& data) = 0;
};

/// The real ioctls.
I2cKernel& linux_i2c_kernel();

/// Where the i2c-N device files are: /dev, or ROTORD_I2C_DEV_ROOT (tests).
std::string i2c_dev_root();

class I2cDev final : public hal::I2c {
 public:
  explicit I2cDev(I2cKernel& kernel) : kernel_(kernel) {}
  ~I2cDev() override;
  I2cDev(const I2cDev&) = delete;
  I2cDev& operator=(const I2cDev&) = delete;

  /// Opens <root>/i2c-<bus> and checks that it is an adapter able to do
  /// plain I2C transfers (an SMBus-only adapter cannot do a repeated start
  /// of any length). False with `error` naming the file and the fix.
  bool open(const std::string& root, int bus, std::string& error);

  bool write(std::uint8_t address, const std::uint8_t* data, std::size_t length) override;
  bool write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                  std::uint8_t* rdata, std::size_t rlength) override;

  const std::string& path() const { return path_; }

 private:
  I2cKernel& kernel_;
  int fd_ = -1;
  std::string path_;
};

}  // namespace rotord::linux_port
