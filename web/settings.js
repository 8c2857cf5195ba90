// The settings page, generated from GET /api/settings/schema (the one
// settings table): each row by its label, in the owner's groups, shown when
// its condition holds here (settings_filter.js), rarely changed ones under
// Advanced. Nothing here lists setting names; the calibration cards
// (calibration.js) name the calibration rows they write.
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const msg = $('msg');
  let schema = null;
  let values = {};
  const fields = {};  // key -> {row, input, error, def}
  const sections = [];  // per group: its fieldset and its Advanced part
  let searching = false;  // whether the last refresh had a search

  function el(tag, attrs, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'class') e.className = v;
      else if (v !== undefined && v !== null) e.setAttribute(k, v);
    }
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  /** A row's help sentence: the table's, served as /settings_help.js. */
  const help = (d) => (typeof rotordSettingsHelp === 'object' && rotordSettingsHelp[d.key]) || '';

  // Each row: the owner's words first, the key small for the REST API.
  function buildRow(d) {
    const id = 'f-' + d.key;
    let input;
    if (d.type === 'bool') {
      input = el('input', { type: 'checkbox', id });
    } else if (d.type === 'enum') {
      input = el('select', { id }, ...d.choices.map((c) => el('option', { value: c }, c)));
    } else if (d.type === 'text' || d.type === 'password') {
      // A password comes back as "********" when one is stored; sending
      // that back keeps it, so an untouched field changes nothing.
      input = el('input', { type: d.type, id, maxlength: d.max, spellcheck: 'false',
        autocomplete: d.type === 'password' ? 'new-password' : 'off', autocapitalize: 'none',
        inputmode: d.format === 'ipv4' ? 'decimal' : undefined,
        placeholder: d.format === 'ipv4' ? '192.168.1.20' : d.type === 'password' ? '(not set)' : undefined });
    } else {
      // Text, not type=number: Chromium's number field drops what it
      // cannot read (a locator typed as JO62QM became 62, 12,5 became
      // 125), so the field keeps what was typed and numberError() says
      // what is wrong. A phone's decimal keypad has no minus sign.
      input = el('input', { type: 'text', id, spellcheck: 'false', autocomplete: 'off',
        inputmode: d.min < 0 ? 'text' : 'decimal' });
    }
    input.dataset.key = d.key;
    const error = el('div', { class: 'error', role: 'alert' });
    const range = d.type === 'float' || d.type === 'int' ? `${d.min} … ${d.max}` : null;
    const length = d.type === 'text' ? `(up to ${d.max} characters${d.default ? `, default ${d.default}` : ''})`
      : d.type === 'password' ? `(${d.min}-${d.max} characters or empty)` : null;
    const row = el('div', { class: 'field' },
      el('label', { for: id }, el('span', { class: 'name' }, d.label || d.key), ' ',
        el('code', { class: 'key', title: 'the key in the REST API and the protocols' }, d.key)),
      el('div', { class: 'input' }, input,
        d.unit ? el('span', { class: 'unit' }, d.unit) : null,
        range ? el('span', { class: 'range' }, `(${range}, default ${d.default})`) : null,
        length ? el('span', { class: 'range' }, length) : null,
        d.restart ? el('span', { class: 'badge', title: 'takes effect after a restart' }, 'restart') : null),
      el('div', { class: 'help' }, help(d)),
      error);
    const f = { row, input, error, def: d };
    // Marked unsaved as it is edited; a number that is not one is refused
    // beside the field while it is typed, not only on Save.
    if (POSITION.includes(d.key)) input.addEventListener('change', () => takeLocator(f));
    input.addEventListener(d.type === 'bool' || d.type === 'enum' ? 'change' : 'input', () => {
      const why = POSITION.includes(d.key) && rotord.locator(input.value) ? null : numberError(f);
      f.error.textContent = why || '';
      f.row.classList.toggle('invalid', !!why);
      refresh();
    });
    fields[d.key] = f;
    return row;
  }

  function build() {
    const groups = $('groups');
    groups.textContent = '';
    for (const g of schema.groups) {
      const main = el('div', {});
      const advanced = el('div', {});
      const details = el('details', { class: 'advanced' }, el('summary', {}, 'Advanced'), advanced);
      // Hidden rows (the password and token hashes) have their own card.
      for (const d of schema.settings.filter((s) => s.group === g && !s.hidden)) {
        (d.advanced ? advanced : main).append(buildRow(d));
      }
      const fs = el('fieldset', { class: 'group' }, el('legend', {}, g), main, details);
      sections.push({ fs, details, summary: details.firstChild, advanced });
      groups.append(fs);
    }
  }

  // The station's position: a Maidenhead locator typed into the latitude or
  // the longitude is understood, and fills both with its square's centre.
  const POSITION = ['station.lat_deg', 'station.lon_deg'];
  function takeLocator(f) {
    const p = rotord.locator(f.input.value);
    if (!p) return;
    const typed = f.input.value.trim().toUpperCase();
    const [lat, lon] = POSITION.map((k) => fields[k]);
    lat.input.value = p[0].toFixed(4);
    lon.input.value = p[1].toFixed(4);
    for (const x of [lat, lon]) { x.error.textContent = ''; x.row.classList.remove('invalid'); }
    rotord.message(msg, `${typed}: ${lat.input.value}, ${lon.input.value}, the centre of the square`, true);
    refresh();
  }

  /** The value a condition tests: the form's, as it stands. */
  function valueOf(key) {
    const f = fields[key];
    return f ? read(f) : values[key];
  }

  /**
   * Shows the rows that apply (or all, when asked) and that the search
   * finds, marks the unsaved ones, and counts both.
   */
  function refresh() {
    if (!schema) return;
    const query = $('search').value.trim();
    const all = $('show-all').checked;
    let shown = 0;
    let elsewhere = 0;
    let unsaved = 0;
    for (const f of Object.values(fields)) {
      const applies = rotordSettingsFilter.holds(f.def.when, schema.platform, valueOf);
      const found = rotordSettingsFilter.found(f.def, query);
      f.row.hidden = !f.forced && (!found || !(applies || all));
      f.row.classList.toggle('not-here', !applies);
      if (!f.row.hidden) shown++;
      else if (found && !applies) elsewhere++;
      const changed = f.def.key in values && read(f) !== values[f.def.key];
      f.row.classList.toggle('changed', changed);
      if (changed) unsaved++;
    }
    for (const s of sections) {
      const advanced = [...s.advanced.children].filter((r) => !r.hidden).length;
      s.details.hidden = advanced === 0;
      s.summary.textContent = `Advanced (${advanced})`;
      // A search opens what it finds; once it is cleared, each Advanced part
      // is as the owner left it.
      if (query && !searching) s.wasOpen = s.details.open;
      if (query) s.details.open = true;
      else if (searching) s.details.open = s.wasOpen;
      s.fs.hidden = s.fs.querySelectorAll('.field:not([hidden])').length === 0;
    }
    searching = !!query;
    $('found').textContent = (query ? `${shown} found` : `${shown} settings`) +
      (elsewhere ? `; ${elsewhere} more do not apply to this platform or drive` : '');
    $('unsaved').textContent = unsaved ? `${unsaved} unsaved` : '';
    $('save').classList.toggle('primary', unsaved > 0);
  }

  function show(v) {
    values = v;
    for (const [key, f] of Object.entries(fields)) {
      f.forced = false;
      if (!(key in v)) continue;
      if (f.def.type === 'bool') f.input.checked = !!v[key];
      else f.input.value = v[key];
      f.error.textContent = '';
      f.row.classList.remove('invalid');
    }
    refresh();
  }

  function read(f) {
    if (f.def.type === 'bool') return f.input.checked;
    if (f.def.type === 'enum') return f.input.value;
    if (f.def.type === 'text' || f.def.type === 'password') return f.input.value;  // as typed: spaces count
    const t = f.input.value.trim();
    return t === '' || isNaN(Number(t)) ? t : Number(t);  // text goes through: the server explains
  }

  // A number as the form shows it: digits, one point for decimals, a sign.
  const NUMBER = /^[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?$/;

  /** What is wrong with a number field's text, or null (range: the server). */
  function numberError(f) {
    if (f.def.type !== 'float' && f.def.type !== 'int') return null;
    const t = f.input.value.trim();
    if (t === '') return 'enter a number';
    if (!NUMBER.test(t)) {
      const pointed = t.replace(',', '.');
      if (NUMBER.test(pointed)) return `not a number: write ${pointed} (a point, not a comma)`;
      return `not a number: write a number such as ${f.def.default}`;
    }
    if (f.def.type === 'int' && !Number.isInteger(Number(t))) return 'a whole number';
    return null;
  }

  function clearErrors() {
    for (const f of Object.values(fields)) { f.error.textContent = ''; f.row.classList.remove('invalid'); }
  }

  /** Shows the result of a settings POST; true on success. */
  function report(r, okText) {
    clearErrors();
    if (r.status === 200) {
      const restart = (r.body && r.body.restart_required) || [];
      $('reboot').hidden = restart.length === 0 && $('reboot').hidden;
      rotord.message(msg, okText + (restart.length ? ` — restart needed for ${restart.join(', ')}` : ''), true);
      return true;
    }
    const errors = (r.body && r.body.errors) || {};
    let first = null;
    for (const [key, reason] of Object.entries(errors)) {
      const f = fields[key];
      if (!f) continue;
      f.error.textContent = reason;
      f.row.classList.add('invalid');
      f.forced = true;  // a refused row is shown, whatever the search or the platform
      first = first || f.input;
    }
    refresh();
    const details = first && first.closest('details');
    if (details) details.open = true;
    rotord.message(msg, (r.body && r.body.error) || `error ${r.status}`, false);
    if (first) first.scrollIntoView({ block: 'center' });
    return false;
  }

  async function reload() {
    const r = await rotord.get('/api/settings');
    if (r.status === 200) show(r.body);
  }

  $('form').addEventListener('submit', async (e) => {
    e.preventDefault();
    for (const k of POSITION) if (fields[k]) takeLocator(fields[k]);
    const changed = {};
    clearErrors();
    let wrong = null;
    for (const [key, f] of Object.entries(fields)) {
      const v = read(f);
      if (v === values[key]) continue;
      const why = numberError(f);
      if (why) {
        // Beside the field, and nothing is sent: a number is never guessed.
        f.error.textContent = why;
        f.row.classList.add('invalid');
        wrong = wrong || f.input;
      }
      changed[key] = v;
    }
    if (wrong) {
      const details = wrong.closest('details');
      if (details) details.open = true;
      wrong.scrollIntoView({ block: 'center' });
      return rotord.message(msg, 'not saved: fix the fields marked', false);
    }
    if (!Object.keys(changed).length) return rotord.message(msg, 'nothing changed', true);
    const r = await rotord.post('/api/settings', changed);
    if (report(r, 'saved')) await reload();
  });

  $('export').addEventListener('click', async () => {
    const r = await rotord.get('/api/settings');
    if (r.status !== 200) return rotord.message(msg, 'cannot read the settings', false);
    const blob = new Blob([JSON.stringify(r.body, null, 2) + '\n'], { type: 'application/json' });
    const a = el('a', { href: URL.createObjectURL(blob), download: 'rotord-settings.json' });
    document.body.append(a);
    a.click();
    a.remove();
  });

  $('import').addEventListener('change', async (e) => {
    const file = e.target.files[0];
    e.target.value = '';
    if (!file) return;
    let doc;
    try { doc = JSON.parse(await file.text()); } catch (err) {
      return rotord.message(msg, `${file.name} is not JSON: ${err.message}`, false);
    }
    const r = await rotord.post('/api/settings', doc);
    if (report(r, `imported ${file.name}`)) await reload();
  });

  $('reset').addEventListener('click', async () => {
    if (!confirm('Reset every setting to its default?')) return;
    const r = await rotord.post('/api/settings/reset', {});
    if (report(r, 'defaults restored')) await reload();
  });

  $('reboot').addEventListener('click', async () => {
    const r = await rotord.post('/api/reboot', {});
    rotord.message(msg, r.status === 202 ? 'restarting…' : (r.body && r.body.error) || 'failed', r.status === 202);
    if (r.status === 202) { $('reboot').hidden = true; setTimeout(reload, 1500); }
  });

  $('search').addEventListener('input', refresh);
  $('show-all').addEventListener('change', refresh);

  // --- live calibration (calibration.js) ---------------------------------------
  const calibration = rotordCalibration.create({ box: $('calibration'), msg, report, reload,
    values: () => values });

  // What start-up could not read from the stored settings (GET /api/status
  // settings_load): each dropped value by name, and whether the controller
  // failed closed because its access settings were among them.
  function showLoadProblems(status) {
    const box = $('load-problems');
    const load = status && status.settings_load;
    box.hidden = !load;
    if (!load) return;
    box.replaceChildren();
    const head = document.createElement('p');
    const strong = document.createElement('strong');
    strong.textContent = load.access_unreadable
      ? 'The access settings could not be read: the controller obeys only STOP and answers status, on every port, until the stored settings are fixed.'
      : 'Some stored settings could not be read and run on their defaults:';
    head.append(strong);
    box.append(head);
    const list = document.createElement('ul');
    for (const d of load.dropped) {
      const li = document.createElement('li');
      li.textContent = (d.key ? d.key + ': ' : '') + d.reason;
      list.append(li);
    }
    if (load.more > 0) {
      const li = document.createElement('li');
      li.textContent = load.more + ' more';
      list.append(li);
    }
    box.append(list);
  }

  async function start() {
    const [s, v, st] = await Promise.all([rotord.get('/api/settings/schema'),
      rotord.get('/api/settings'), rotord.get('/api/status')]);
    if (s.status !== 200 || v.status !== 200) {
      return rotord.message(msg, 'cannot load the settings from the controller', false);
    }
    schema = s.body;
    build();
    show(v.body);
    // Links to one setting (settings.html#f-station.lat_deg, from the
    // control and track pages): the field exists only now, and is shown
    // even when Advanced is closed or it does not apply here.
    const target = location.hash && $(decodeURIComponent(location.hash.slice(1)));
    const f = target && fields[target.dataset.key];
    if (f) {
      f.forced = true;
      refresh();
      const details = f.row.closest('details');
      if (details) details.open = true;
      target.scrollIntoView({ block: 'center' });
      target.focus();
    }
    if (st.status === 200) calibration.update(st.body);
    if (st.status === 200) showLoadProblems(st.body);
    rotordAccess.wire(msg);
    rotordAccess.card($('access'));
    rotord.live((status) => calibration.update(status));
  }
  start();
})();
