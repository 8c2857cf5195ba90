// Writes the help sentence of every setting, from the one settings table
// (core/settings/settings_table.def), as a web asset: settings_help.js,
// `const rotordSettingsHelp = {"<key>": "<help>", ...}`. The help is the
// table's like every other column; it is served gzipped with the web UI
// rather than compiled into the core's rodata, where 22 KB of plain text
// did not fit the Pico W's flash budget (tests/embedded/budgets.txt).
// Fails (exit 1) when a row has no help, so no setting goes without one.
// node settings_help.mjs <settings_table.def> <out.js>
import { readFileSync, writeFileSync } from 'node:fs';

const [table, out] = process.argv.slice(2);
const text = readFileSync(table, 'utf8');
const rows = text.split(/\n(?=SETTING\()/).filter((c) => c.startsWith('SETTING('));
const help = {};
for (const row of rows) {
  const key = /^SETTING\(\s*\w+,\s*"([^"]+)"/.exec(row)?.[1];
  // The row ends at the first '")' that ends a line (a literal holds no
  // newline); its last argument is the string literal just before it.
  const end = row.search(/"\)[ \t]*(\n|$)/);
  const literal = end < 0 ? null : /("(?:[^"\\]|\\.)*")$/.exec(row.slice(0, end + 1))?.[1];
  if (!key || !literal) {
    console.error(`${table}: cannot read the help of ${key ?? row.slice(0, 60)}`);
    process.exit(1);
  }
  const sentence = JSON.parse(literal);  // C's \\ and \" read as JSON's
  if (!sentence.trim()) {
    console.error(`${table}: ${key} has no help`);
    process.exit(1);
  }
  help[key] = sentence;
}
writeFileSync(out, `// Generated from core/settings/settings_table.def by web/tools/settings_help.mjs.\n` +
  `const rotordSettingsHelp = ${JSON.stringify(help)};\n`);
