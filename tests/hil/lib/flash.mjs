// The Pico's flash as the firmware sees it: the settings slots
// (core/storage/flash_slots.hpp) written into the image before boot, and
// erase and program, which rp2040js 1.4.1 does not model (its SSI only
// answers status reads), modelled at the bootrom's routines.

export const FLASH_BYTES = 2 * 1024 * 1024; // PICO_FLASH_SIZE_BYTES of the pico_w board
export const SETTINGS_REGION_BYTES = 32 * 1024; // PicoFlash::kRegionBytes (ROTORD_SETTINGS_FLASH_BYTES), at the very end
const SECTOR = 4096;
const PAGE = 256;
const MAGIC = 0x54455352; // "RSET"
const HEADER_BYTES = 24;

/** zlib's CRC-32 (core/util/crc32.hpp). */
export function crc32(bytes, crc = 0) {
  crc = ~crc >>> 0;
  for (const b of bytes) {
    crc ^= b;
    for (let k = 0; k < 8; k++) crc = crc & 1 ? (crc >>> 1) ^ 0xedb88320 : crc >>> 1;
  }
  return ~crc >>> 0;
}

/** Slot `slot` (0/1) of the settings region, holding `document`, as FlashSlots::save writes it. */
export function writeSettingsSlot(flash, document, { slot = 0, sequence = 1 } = {}) {
  const slotBytes = Math.floor(SETTINGS_REGION_BYTES / 2 / SECTOR) * SECTOR;
  const base = FLASH_BYTES - SETTINGS_REGION_BYTES + slot * slotBytes;
  const payload = new TextEncoder().encode(document);
  if (payload.length > slotBytes - PAGE) throw new Error('settings document larger than a slot');
  flash.fill(0xff, base, base + slotBytes);
  flash.set(payload, base + PAGE);
  const header = new Uint8Array(HEADER_BYTES);
  const view = new DataView(header.buffer);
  view.setUint32(0, MAGIC, true);
  view.setUint16(4, 1, true); // format
  view.setUint16(6, HEADER_BYTES, true);
  view.setUint32(8, sequence, true);
  view.setUint32(12, payload.length, true);
  view.setUint32(16, crc32(payload), true);
  view.setUint32(20, crc32(header.subarray(0, 20)), true);
  flash.set(header, base);
}

/** The newest valid settings document in the flash, or null (for checks). */
export function readSettings(flash) {
  const slotBytes = Math.floor(SETTINGS_REGION_BYTES / 2 / SECTOR) * SECTOR;
  let best = null;
  for (let slot = 0; slot < 2; slot++) {
    const base = FLASH_BYTES - SETTINGS_REGION_BYTES + slot * slotBytes;
    const view = new DataView(flash.buffer, flash.byteOffset + base, HEADER_BYTES);
    if (view.getUint32(0, true) !== MAGIC) continue;
    if (crc32(flash.subarray(base, base + 20)) !== view.getUint32(20, true)) continue;
    const length = view.getUint32(12, true);
    const payload = flash.subarray(base + PAGE, base + PAGE + length);
    if (crc32(payload) !== view.getUint32(16, true)) continue;
    const sequence = view.getUint32(8, true);
    if (!best || sequence > best.sequence)
      best = { slot, sequence, document: new TextDecoder().decode(payload) };
  }
  return best;
}

/**
 * Flash erase and program, which rp2040js 1.4.1 does not model (its SSI only
 * answers status reads, so the bootrom's SPI commands change nothing). The
 * harness models the bootrom's two routines instead: their entries (found
 * through the ROM's function table, codes 'RE' and 'RP') are overwritten
 * with `bkpt #n; bx lr`, and the breakpoint applies the operation to
 * rp2040.flash with NOR semantics (erase to FF by whole 4 KB sectors,
 * program ANDs). Everything around them runs as on the chip: the SDK's
 * flash_safe_execute, connect_internal_flash, flash_exit_xip, the cache flush
 * and the return to XIP through boot2. Installed on a fresh RP2040 after its
 * bootrom is loaded.
 */
const BKPT_ERASE = 0xe5;
const BKPT_PROGRAM = 0x9e;

function romFunction(rp2040, code) {
  const rom = new DataView(rp2040.bootrom.buffer);
  let p = rom.getUint16(0x14, true); // rom_func_table
  for (;;) {
    const c = rom.getUint16(p, true);
    if (c === 0) return -1;
    if (c === code) return rom.getUint16(p + 2, true) & ~1;
    p += 4;
  }
}

export function installFlashModel(rp2040, stats = { erases: 0, programs: 0 }) {
  const rom = new DataView(rp2040.bootrom.buffer);
  const erase = romFunction(rp2040, 0x4552); // 'R','E'
  const program = romFunction(rp2040, 0x5052); // 'R','P'
  if (erase < 0 || program < 0) throw new Error('bootrom without flash_range_erase/program');
  rom.setUint16(erase, 0xbe00 | BKPT_ERASE, true);
  rom.setUint16(erase + 2, 0x4770, true); // bx lr
  rom.setUint16(program, 0xbe00 | BKPT_PROGRAM, true);
  rom.setUint16(program + 2, 0x4770, true);
  const core = rp2040.core;
  const previous = rp2040.onBreak;
  rp2040.onBreak = (code) => {
    const r = core.registers;
    if (code === BKPT_ERASE) {
      // flash_range_erase(addr, count, block_size, block_cmd)
      const start = r[0] & ~(SECTOR - 1);
      const end = (r[0] + r[1] + SECTOR - 1) & ~(SECTOR - 1);
      rp2040.flash.fill(0xff, start, end);
      stats.erases += (end - start) / SECTOR;
    } else if (code === BKPT_PROGRAM) {
      // flash_range_program(addr, data, count)
      for (let i = 0; i < r[2]; i++) rp2040.flash[r[0] + i] &= rp2040.readUint8(r[1] + i);
      stats.programs += Math.ceil(r[2] / PAGE);
    } else {
      previous(code);
      return;
    }
    core.breakRewind = 0; // carry on with the bx lr
  };
  return stats;
}
