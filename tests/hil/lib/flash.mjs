// The Pico W's flash as the firmware sees it: the settings slots
// (core/storage/flash_slots.hpp) written into the image before boot, and a
// model of the flash chip's erase and program commands, which rp2040js
// 1.4.1's SSI ignores (it only answers status reads).

export const FLASH_BYTES = 2 * 1024 * 1024; // PICO_FLASH_SIZE_BYTES of the pico_w board
export const SETTINGS_REGION_BYTES = 16 * 1024; // PicoFlash::kRegionBytes, at the very end
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
 * The flash chip behind the SSI: the bootrom's flash_range_erase and
 * flash_range_program send SPI commands through SSI DR0 between chip-select
 * edges (IO_QSPI's SS output override). Write enable (06), sector erase (20),
 * 32/64 KB block erase (52/D8) and page program (02) are applied to
 * rp2040.flash with NOR semantics (erase to FF, program ANDs); everything
 * else (status reads, XIP set-up) is ignored as before. Installed on a fresh
 * RP2040 before it runs.
 */
export function installFlashModel(rp2040, stats = { erases: 0, programs: 0 }) {
  const ssi = rp2040.peripherals[0x18000];
  const ioQspi = rp2040.peripherals[0x40018];
  let selected = false;
  let bytes = [];
  let writeEnabled = false;
  const execute = () => {
    const [cmd, a2, a1, a0] = bytes;
    const addr = ((a2 << 16) | (a1 << 8) | a0) & (rp2040.flash.length - 1);
    if (cmd === 0x06) writeEnabled = true;
    else if (cmd === 0x04) writeEnabled = false;
    else if (writeEnabled && bytes.length >= 4 && (cmd === 0x20 || cmd === 0x52 || cmd === 0xd8)) {
      const size = cmd === 0x20 ? 4096 : cmd === 0x52 ? 32768 : 65536;
      const start = addr & ~(size - 1);
      rp2040.flash.fill(0xff, start, start + size);
      stats.erases++;
      writeEnabled = false;
    } else if (writeEnabled && bytes.length > 4 && cmd === 0x02) {
      const pageStart = addr & ~(PAGE - 1);
      for (let i = 4; i < bytes.length; i++) {
        const at = pageStart + ((addr + i - 4) & (PAGE - 1)); // wraps inside the page, as the chip does
        rp2040.flash[at] &= bytes[i];
      }
      stats.programs++;
      writeEnabled = false;
    }
  };
  const ssiWrite = ssi.writeUint32.bind(ssi);
  ssi.writeUint32 = (offset, value) => {
    if (offset === 0x60 && selected) bytes.push(value & 0xff);
    ssiWrite(offset, value);
  };
  // GPIO_QSPI_SS_CTRL (io[1].ctrl), OUTOVER bits 9:8: 2 = drive low (selected), 3 = high.
  let ssCtrl = 0;
  const ioRead = ioQspi.readUint32.bind(ioQspi);
  ioQspi.readUint32 = (offset) => (offset === 0x0c ? ssCtrl : ioRead(offset));
  const ioWrite = ioQspi.writeUint32.bind(ioQspi);
  ioQspi.writeUint32 = (offset, value) => {
    if (offset !== 0x0c) return ioWrite(offset, value);
    ssCtrl = value;
    const outover = (value >> 8) & 3;
    if (outover === 2 && !selected) {
      selected = true;
      bytes = [];
    } else if (outover !== 2 && selected) {
      selected = false;
      execute();
    }
  };
  return stats;
}
