#pragma once
// A fake CDC ACM interface for the Pico W's USB code on the host
// (usb_cdc_link.cpp, log_port.cpp): it behaves as TinyUSB's CDC class does
// for them, a bounded TX FIFO the host drains when it reads, an RX FIFO the
// host fills, DTR and an open counter. The hardware boundary: everything
// above it is the firmware's code.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "usb_cdc_link.hpp"

namespace rotord::testing {

class FakeCdc final : public usb_port::CdcPort {
 public:
  static constexpr std::size_t kFifoBytes = 256;  // CFG_TUD_CDC_TX_BUFSIZE

  // --- The host's side ---------------------------------------------------
  void plug() { mounted_ = true; }
  void unplug() {
    mounted_ = false;
    dtr_ = false;  // a bus reset clears the line state
  }
  void open() {
    dtr_ = true;
    ++opens_;
  }
  void close() { dtr_ = false; }
  void send(std::string bytes) { rx_ += bytes; }
  /// What the host reads: everything the device has queued and flushed.
  std::string take() {
    std::string got = tx_;
    tx_.clear();
    return got;
  }
  std::size_t unread_input() const { return rx_.size(); }
  std::size_t queued_output() const { return tx_.size(); }
  int flushes() const { return flushes_; }

  // --- CdcPort -------------------------------------------------------------
  bool connected() const override { return mounted_; }
  bool dtr() const override { return dtr_; }
  std::uint32_t opens() const override { return opens_; }
  std::size_t read(char* buffer, std::size_t max_bytes) override {
    const std::size_t n = std::min(max_bytes, rx_.size());
    rx_.copy(buffer, n);
    rx_.erase(0, n);
    return n;
  }
  std::size_t write_available() const override { return kFifoBytes - tx_.size(); }
  std::size_t write(const char* data, std::size_t bytes) override {
    const std::size_t n = std::min(bytes, write_available());
    tx_.append(data, n);
    return n;
  }
  void flush() override { ++flushes_; }
  void discard_output() override { tx_.clear(); }
  void discard_input() override { rx_.clear(); }

 private:
  bool mounted_ = false;
  bool dtr_ = false;
  std::uint32_t opens_ = 0;
  std::string rx_, tx_;
  int flushes_ = 0;
};

}  // namespace rotord::testing
