// lib/elf.mjs: the symbols the harness reads the firmware's heap through
// (end, __StackLimit, newlib's __malloc_max_sbrked_mem), from a 32-bit
// little-endian ELF file laid out as arm-none-eabi-ld writes one: the ELF
// header, a symbol table whose names are in the string table it links to.
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import { elfSymbols } from '../lib/elf.mjs';

/** An ELF32 file with sections [null, .strtab, .symtab] holding `symbols` ({ name, value, size }). */
function elf32(symbols) {
  const names = ['', ...symbols.map((s) => s.name)];
  const strtab = Buffer.from(names.join('\0') + '\0', 'latin1');
  const nameOffset = (i) => names.slice(0, i).reduce((n, s) => n + s.length + 1, 0);
  const symtab = Buffer.alloc(16 * (symbols.length + 1)); // entry 0: the null symbol
  symbols.forEach((s, i) => {
    const e = 16 * (i + 1);
    symtab.writeUInt32LE(nameOffset(i + 1), e);
    symtab.writeUInt32LE(s.value, e + 4);
    symtab.writeUInt32LE(s.size, e + 8);
  });
  const header = Buffer.alloc(52);
  header.writeUInt32BE(0x7f454c46, 0);
  header[4] = 1; // ELFCLASS32
  header[5] = 1; // little-endian
  const strOff = 52;
  const symOff = strOff + strtab.length;
  const shOff = symOff + symtab.length;
  header.writeUInt32LE(shOff, 32);
  header.writeUInt16LE(40, 46); // e_shentsize
  header.writeUInt16LE(3, 48); // e_shnum
  const sections = Buffer.alloc(40 * 3);
  const section = (i, type, offset, size, link, entsize) => {
    const h = 40 * i;
    sections.writeUInt32LE(type, h + 4);
    sections.writeUInt32LE(offset, h + 16);
    sections.writeUInt32LE(size, h + 20);
    sections.writeUInt32LE(link, h + 24);
    sections.writeUInt32LE(entsize, h + 36);
  };
  section(1, 3, strOff, strtab.length, 0, 0); // SHT_STRTAB
  section(2, 2, symOff, symtab.length, 1, 16); // SHT_SYMTAB, names in section 1
  return Buffer.concat([header, strtab, symtab, sections]);
}

test('reads each symbol of the symbol table by name, with its value and size', () => {
  const dir = mkdtempSync(join(tmpdir(), 'rotord-elf-'));
  try {
    const path = join(dir, 'image.elf');
    writeFileSync(path, elf32([
      { name: 'end', value: 0x2003f610, size: 0 },
      { name: '__StackLimit', value: 0x20040000, size: 0 },
      { name: '__malloc_max_sbrked_mem', value: 0x200274c8, size: 4 },
    ]));
    const symbols = elfSymbols(path);
    assert.deepEqual(symbols.get('end'), { value: 0x2003f610, size: 0 });
    assert.equal(symbols.get('__StackLimit').value - symbols.get('end').value, 2544);
    assert.deepEqual(symbols.get('__malloc_max_sbrked_mem'), { value: 0x200274c8, size: 4 });
    assert.equal(symbols.has(''), false);
    assert.equal(symbols.size, 3);
  } finally {
    rmSync(dir, { recursive: true });
  }
});

test('refuses a file that is not a 32-bit little-endian ELF', () => {
  const dir = mkdtempSync(join(tmpdir(), 'rotord-elf-'));
  try {
    const path = join(dir, 'image.bin');
    writeFileSync(path, Buffer.alloc(64));
    assert.throws(() => elfSymbols(path), /not a 32-bit little-endian ELF/);
    const elf64 = elf32([]);
    elf64[4] = 2; // ELFCLASS64
    writeFileSync(path, elf64);
    assert.throws(() => elfSymbols(path), /not a 32-bit little-endian ELF/);
  } finally {
    rmSync(dir, { recursive: true });
  }
});
