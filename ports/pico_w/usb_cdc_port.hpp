#pragma once
// TinyUSB's CDC interface as the link's CdcPort (usb_cdc_link.hpp): the
// hardware side of the Pico W's USB protocol port.
#include "usb_cdc_link.hpp"
#include "usb_device.h"

namespace rotord::pico_w {

class TinyUsbCdcPort final : public usb_port::CdcPort {
 public:
  explicit TinyUsbCdcPort(std::uint8_t itf) : itf_(itf) {}

  bool connected() const override { return rotord_usb_cdc_ready(itf_); }
  bool dtr() const override { return rotord_usb_cdc_dtr(itf_); }
  std::uint32_t opens() const override { return rotord_usb_cdc_opens(itf_); }
  std::size_t read(char* buffer, std::size_t max_bytes) override {
    return rotord_usb_cdc_read(itf_, buffer, static_cast<std::uint32_t>(max_bytes));
  }
  std::size_t write_available() const override { return rotord_usb_cdc_write_available(itf_); }
  std::size_t write(const char* data, std::size_t bytes) override {
    return rotord_usb_cdc_write(itf_, data, static_cast<std::uint32_t>(bytes));
  }
  void flush() override { rotord_usb_cdc_flush(itf_); }
  void discard_output() override { rotord_usb_cdc_discard_output(itf_); }
  void discard_input() override { rotord_usb_cdc_discard_input(itf_); }

 private:
  std::uint8_t itf_;
};

}  // namespace rotord::pico_w
