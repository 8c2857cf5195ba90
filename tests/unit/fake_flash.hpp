#pragma once
// A NOR flash in RAM for FlashSlots tests: erase sets 0xFF, program ANDs
// bits in, misaligned calls fail the test. It can cut the power part-way
// through a program or an erase; after that every call fails until
// power_on(), and the memory keeps what was written, as a real chip does.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "hal/flash.hpp"

namespace rotord::testing {

class FakeFlash final : public hal::Flash {
 public:
  FakeFlash(std::size_t size, std::size_t erase, std::size_t page)
      : mem(size, 0xFF), erase_(erase), page_(page) {}

  std::vector<std::uint8_t> mem;
  int erases = 0;
  int programs = 0;
  /// Bytes that may still be programmed before the power fails (-1: no limit).
  long program_budget = -1;
  /// Erase blocks that may still be erased before the power fails (-1: no limit).
  long erase_budget = -1;
  bool dead = false;

  void power_on() {
    dead = false;
    program_budget = erase_budget = -1;
  }

  std::size_t size() const override { return mem.size(); }
  std::size_t erase_size() const override { return erase_; }
  std::size_t program_size() const override { return page_; }

  bool read(std::size_t offset, void* out, std::size_t length) override {
    if (dead || offset + length > mem.size()) return false;
    std::memcpy(out, mem.data() + offset, length);
    return true;
  }

  bool erase(std::size_t offset, std::size_t length) override {
    if (dead) return false;
    if (offset % erase_ != 0 || length % erase_ != 0 || offset + length > mem.size()) {
      ADD_FAILURE() << "misaligned erase " << offset << "+" << length;
      return false;
    }
    ++erases;
    for (std::size_t block = offset; block < offset + length; block += erase_) {
      if (erase_budget == 0) {
        // The cut lands inside this block: half of it is erased.
        std::memset(mem.data() + block, 0xFF, erase_ / 2);
        dead = true;
        return false;
      }
      if (erase_budget > 0) --erase_budget;
      std::memset(mem.data() + block, 0xFF, erase_);
    }
    return true;
  }

  bool program(std::size_t offset, const void* data, std::size_t length) override {
    if (dead) return false;
    if (offset % page_ != 0 || length % page_ != 0 || offset + length > mem.size()) {
      ADD_FAILURE() << "misaligned program " << offset << "+" << length;
      return false;
    }
    ++programs;
    const auto* src = static_cast<const std::uint8_t*>(data);
    for (std::size_t n = 0; n < length; ++n) {
      if (program_budget == 0) {
        dead = true;
        return false;
      }
      if (program_budget > 0) --program_budget;
      mem[offset + n] &= src[n];  // NOR: bits only go from 1 to 0
    }
    return true;
  }

 private:
  std::size_t erase_;
  std::size_t page_;
};

}  // namespace rotord::testing
