// Writes the help sentence of every setting, from the one settings table
// (core/settings/settings_table.def), as a web asset: settings_help.js,
// `const rotordSettingsHelp = {"<key>": "<help>", ...}`. The help is the
// table's like every other column; it is served gzipped with the web UI
// rather than compiled into the core's rodata, where 22 KB of plain text
// did not fit the Pico W's flash budget (tests/embedded/budgets.txt).
// Fails (exit 1) when a row has no help, so no setting goes without one.
//
// The table's two axis blocks expand the per-axis rows (axis_settings.def,
// next to it) as the C++ preprocessor does (axis_expand.def): once as az.*,
// once as el.* without the azimuth's own rows (AZ_SETTING). The elevation's
// help is the second value of AZ_EL(az, el) when given, else the azimuth's
// with "azimuth" read "elevation" and "az." read "el.".
// node settings_help.mjs <settings_table.def> <out.js>
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';

const [table, out] = process.argv.slice(2);
const axisTable = join(dirname(table), 'axis_settings.def');

function fail(message) {
  console.error(message);
  process.exit(1);
}

/** The arguments of the macro call that starts at text[open] ('('), as raw text. */
function macroArguments(text, open) {
  const args = [];
  let depth = 0;
  let start = open + 1;
  for (let i = open; i < text.length; ++i) {
    const c = text[i];
    if (c === '"') {
      for (++i; text[i] !== '"'; ++i) if (text[i] === '\\') ++i;
    } else if (c === '(') {
      ++depth;
    } else if (c === ')' || (c === ',' && depth === 1)) {
      if (c === ')' && --depth > 0) continue;
      args.push(text.slice(start, i).trim());
      start = i + 1;
      if (c === ')') return { args, end: i + 1 };
    }
  }
  return null;
}

/** A C string literal, or adjacent ones, as a JS string (C's \\ and \" read as JSON's). */
function literal(arg) {
  const parts = arg.match(/"(?:[^"\\]|\\.)*"/g);
  if (!parts || parts.join('').length !== arg.replace(/\s+(?=")/g, '').length) return null;
  return parts.map((p) => JSON.parse(p)).join('');
}

/** Every call of one of `macros` in `text`, in order: { macro, args }. */
function calls(text, macros) {
  const found = [];
  const re = new RegExp(`^(${macros.join('|')})\\(`, 'gm');
  for (let m; (m = re.exec(text));) {
    const parsed = macroArguments(text, m.index + m[1].length);
    if (!parsed) fail(`${table}: cannot read the row at ${text.slice(m.index, m.index + 60)}`);
    found.push({ macro: m[1], args: parsed.args });
    re.lastIndex = parsed.end;
  }
  return found;
}

/** The help of a per-axis row on one axis. */
function axisHelp(arg, axis) {
  const azEl = /^AZ_EL\(/.test(arg) ? macroArguments(arg, 'AZ_EL'.length) : null;
  if (azEl) return literal(azEl.args[axis === 'az' ? 0 : 1]);
  const help = literal(arg);
  if (help === null || axis === 'az') return help;
  return help.replaceAll('azimuth', 'elevation').replace(/\baz\./g, 'el.');
}

const axisRows = calls(readFileSync(axisTable, 'utf8'), ['AXIS_SETTING', 'AZ_SETTING']);
const help = {};
function add(key, sentence) {
  if (sentence === null) fail(`${table}: cannot read the help of ${key}`);
  if (!sentence.trim()) fail(`${table}: ${key} has no help`);
  help[key] = sentence;
}

// The table's rows and its two axis blocks, in the table's order.
const text = readFileSync(table, 'utf8');
const re = /^SETTING\(|^#define ROTORD_AXIS_EL ([01])\s*\n#include "settings\/axis_expand\.def"/gm;
for (let m; (m = re.exec(text));) {
  if (m[1] !== undefined) {
    const axis = m[1] === '1' ? 'el' : 'az';
    for (const row of axisRows) {
      if (axis === 'el' && row.macro === 'AZ_SETTING') continue;
      add(`${axis}.${literal(row.args[1])}`, axisHelp(row.args[12], axis));
    }
    continue;
  }
  const parsed = macroArguments(text, m.index + 'SETTING'.length);
  if (!parsed || parsed.args.length !== 13) fail(`${table}: cannot read the row at ${text.slice(m.index, m.index + 60)}`);
  add(literal(parsed.args[1]), literal(parsed.args[12]));
  re.lastIndex = parsed.end;
}
writeFileSync(out, `// Generated from core/settings/settings_table.def by web/tools/settings_help.mjs.\n` +
  `const rotordSettingsHelp = ${JSON.stringify(help)};\n`);
