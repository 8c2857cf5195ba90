// Symbols of a 32-bit little-endian ELF image (the firmware's .elf): enough
// of the format to read .symtab, so the harness can look at the firmware's
// own variables in the emulated RAM (the heap's high-water mark) without a
// toolchain at run time.
import { readFileSync } from 'node:fs';

const SHT_SYMTAB = 2;

/** Map of symbol name -> { value, size } (the last of a name wins; locals too). */
export function elfSymbols(path) {
  const data = readFileSync(path);
  if (data.readUInt32BE(0) !== 0x7f454c46 || data[4] !== 1 || data[5] !== 1)
    throw new Error(`${path}: not a 32-bit little-endian ELF file`);
  const shoff = data.readUInt32LE(32);
  const shentsize = data.readUInt16LE(46);
  const shnum = data.readUInt16LE(48);
  const section = (i) => {
    const h = shoff + i * shentsize;
    return {
      type: data.readUInt32LE(h + 4),
      offset: data.readUInt32LE(h + 16),
      size: data.readUInt32LE(h + 20),
      link: data.readUInt32LE(h + 24),
      entsize: data.readUInt32LE(h + 36),
    };
  };
  const symbols = new Map();
  for (let i = 0; i < shnum; i++) {
    const s = section(i);
    if (s.type !== SHT_SYMTAB) continue;
    const strtab = section(s.link);
    for (let off = s.offset; off + 16 <= s.offset + s.size; off += s.entsize || 16) {
      const nameOff = data.readUInt32LE(off);
      if (nameOff === 0) continue;
      const start = strtab.offset + nameOff;
      const name = data.toString('latin1', start, data.indexOf(0, start));
      symbols.set(name, { value: data.readUInt32LE(off + 4), size: data.readUInt32LE(off + 8) });
    }
  }
  return symbols;
}
