#pragma once
// hal::Flash over the last sectors of the Pico W's 2 MB flash, for the
// settings slots (core/storage/flash_slots). Erase and program run through
// the SDK's flash_safe_execute, which keeps interrupts (and the other core,
// if it ever runs) away from the flash while XIP is off.
#include <cstddef>

#include "hal/flash.hpp"

namespace rotord::pico_w {

class PicoFlash final : public hal::Flash {
 public:
  /// Two 8 KB slots: the settings document is ~4 KB today and grows with the
  /// settings table; 4 KB slots would leave no headroom. The sizes come from
  /// CMakeLists.txt, whose build check keeps the image below both regions.
  static constexpr std::size_t kRegionBytes = ROTORD_SETTINGS_FLASH_BYTES;
  /// The stored TLEs (tracking/tle_catalog.hpp, at most 4.1 KB of text): two
  /// 8 KB slots right below the settings.
  static constexpr std::size_t kTleRegionBytes = ROTORD_TLE_FLASH_BYTES;
  /// The wear odometer (docs/care.md): eight 4 KB slots below the TLEs,
  /// written in turn, so each sector is erased once every eight saves.
  static constexpr std::size_t kOdometerRegionBytes = ROTORD_ODOMETER_FLASH_BYTES;
  static constexpr int kOdometerSlots = 8;

  /// A region of `size` bytes ending `end_gap` bytes before the end of the
  /// flash: the settings (default) at the very end, the TLEs below them.
  explicit PicoFlash(std::size_t end_gap = 0, std::size_t size = kRegionBytes)
      : size_(size), end_gap_(end_gap) {}

  /// True when the region lies after the program image (a larger image
  /// would be overwritten by the first save).
  bool region_free() const;

  std::size_t size() const override { return size_; }
  std::size_t erase_size() const override;
  std::size_t program_size() const override;
  bool read(std::size_t offset, void* out, std::size_t length) override;
  bool erase(std::size_t offset, std::size_t length) override;
  bool program(std::size_t offset, const void* data, std::size_t length) override;

 private:
  /// Where the region starts, as an offset into the flash.
  std::size_t region_offset() const;
  bool in_region(std::size_t offset, std::size_t length) const;

  std::size_t size_;
  std::size_t end_gap_;
};

}  // namespace rotord::pico_w
