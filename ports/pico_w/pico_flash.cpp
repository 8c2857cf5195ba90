#include "pico_flash.hpp"

#include <cstdint>
#include <cstring>

#include "hardware/flash.h"
#include "hardware/watchdog.h"
#include "pico/flash.h"

extern "C" char __flash_binary_end;  // from the SDK's linker script

// The build's flash layout check (cmake/check-flash-layout.cmake) assumes
// this flash size.
static_assert(PICO_FLASH_SIZE_BYTES == ROTORD_FLASH_BYTES,
              "ROTORD_FLASH_BYTES (CMakeLists.txt) must be the board's flash size");

namespace rotord::pico_w {
namespace {

// Generous: flash_safe_execute only waits this long to get exclusive access.
constexpr std::uint32_t kSafeTimeoutMs = 100;

struct EraseArgs {
  std::uint32_t offset;
  std::size_t length;
};
struct ProgramArgs {
  std::uint32_t offset;
  const std::uint8_t* data;
  std::size_t length;
};

void do_erase(void* p) {
  const auto* a = static_cast<const EraseArgs*>(p);
  flash_range_erase(a->offset, a->length);
}
void do_program(void* p) {
  const auto* a = static_cast<const ProgramArgs*>(p);
  flash_range_program(a->offset, a->data, a->length);
}

}  // namespace

std::size_t PicoFlash::region_offset() const {
  return PICO_FLASH_SIZE_BYTES - end_gap_ - size_;
}

bool PicoFlash::in_region(std::size_t offset, std::size_t length) const {
  return offset <= size_ && length <= size_ - offset;
}

bool PicoFlash::region_free() const {
  return reinterpret_cast<std::uintptr_t>(&__flash_binary_end) <= XIP_BASE + region_offset();
}

std::size_t PicoFlash::erase_size() const {
  return FLASH_SECTOR_SIZE;
}

std::size_t PicoFlash::program_size() const {
  return FLASH_PAGE_SIZE;
}

bool PicoFlash::read(std::size_t offset, void* out, std::size_t length) {
  if (!in_region(offset, length)) return false;
  // The flash is memory-mapped (XIP); erase and program flush the cache.
  std::memcpy(out, reinterpret_cast<const void*>(XIP_BASE + region_offset() + offset), length);
  return true;
}

bool PicoFlash::erase(std::size_t offset, std::size_t length) {
  if (!in_region(offset, length) || !region_free()) return false;
  // One sector at a time, feeding the watchdog in between: a sector erase
  // takes 45 ms typically and up to 400 ms, with interrupts off.
  for (std::size_t done = 0; done < length; done += FLASH_SECTOR_SIZE) {
    EraseArgs args{static_cast<std::uint32_t>(region_offset() + offset + done), FLASH_SECTOR_SIZE};
    if (flash_safe_execute(&do_erase, &args, kSafeTimeoutMs) != PICO_OK) return false;
    watchdog_update();
  }
  return true;
}

bool PicoFlash::program(std::size_t offset, const void* data, std::size_t length) {
  if (!in_region(offset, length) || !region_free()) return false;
  ProgramArgs args{static_cast<std::uint32_t>(region_offset() + offset),
                   static_cast<const std::uint8_t*>(data), length};
  return flash_safe_execute(&do_program, &args, kSafeTimeoutMs) == PICO_OK;
}

}  // namespace rotord::pico_w
