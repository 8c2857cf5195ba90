#include "i2c_dev.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "host_path.hpp"

namespace rotord::linux_port {
namespace {

class LinuxI2cKernel final : public I2cKernel {
 public:
  int functionality(int fd, unsigned long& funcs) override {
    return ::ioctl(fd, I2C_FUNCS, &funcs);
  }
  int transfer(int fd, i2c_rdwr_ioctl_data& data) override { return ::ioctl(fd, I2C_RDWR, &data); }
};

}  // namespace

I2cKernel& linux_i2c_kernel() {
  static LinuxI2cKernel kernel;
  return kernel;
}

std::string i2c_dev_root() {
  return host_path("ROTORD_I2C_DEV_ROOT", "/dev");
}

I2cDev::~I2cDev() {
  if (fd_ >= 0) ::close(fd_);
}

bool I2cDev::open(const std::string& root, int bus, std::string& error) {
  path_ = root + "/i2c-" + std::to_string(bus);
  fd_ = ::open(path_.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) {
    error = "cannot open " + path_ + ": " + std::strerror(errno) +
            (errno == ENOENT ? " (is the I2C bus enabled? on a Raspberry Pi dtparam=i2c_arm=on, "
                               "see docs/gpiod.md)"
                             : "");
    return false;
  }
  unsigned long funcs = 0;
  if (kernel_.functionality(fd_, funcs) < 0) {
    error = path_ + " is not an I2C adapter: " + std::strerror(errno);
    return false;
  }
  if ((funcs & I2C_FUNC_I2C) == 0) {
    error = path_ + " is an SMBus-only adapter; the magnetometer needs plain I2C transfers";
    return false;
  }
  return true;
}

bool I2cDev::write(std::uint8_t address, const std::uint8_t* data, std::size_t length) {
  i2c_msg msg{address, 0, static_cast<__u16>(length), const_cast<__u8*>(data)};
  i2c_rdwr_ioctl_data transaction{&msg, 1};
  return fd_ >= 0 && kernel_.transfer(fd_, transaction) == 1;
}

bool I2cDev::write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                        std::uint8_t* rdata, std::size_t rlength) {
  // The kernel takes a non-const buffer for both directions; it only reads
  // the first message's.
  i2c_msg msgs[2] = {
      {address, 0, static_cast<__u16>(wlength), const_cast<__u8*>(wdata)},
      {address, I2C_M_RD, static_cast<__u16>(rlength), rdata},
  };
  i2c_rdwr_ioctl_data transaction{msgs, 2};
  return fd_ >= 0 && kernel_.transfer(fd_, transaction) == 2;
}

}  // namespace rotord::linux_port
