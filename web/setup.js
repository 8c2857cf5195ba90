// The set-up page (docs/commissioning.md): model, wiring, self-commissioning
// with its evidence, station, access. Everything goes through the REST API.
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  let models = [];
  let values = {};

  function cell(tr, text) {
    const td = document.createElement('td');
    td.textContent = text;
    tr.appendChild(td);
  }
  function rows(tbody, list) {
    tbody.textContent = '';
    for (const r of list) {
      const tr = document.createElement('tr');
      for (const t of r) cell(tr, t);
      tbody.appendChild(tr);
    }
  }

  async function loadSettings() {
    const r = await rotord.get('/api/settings');
    if (r.status === 200) values = r.body;
  }

  // --- 1. the model
  // The model shown after a reload: the one chosen in this tab (the
  // session's progress), else the one the settings in force match best
  // (what was saved): no figure differs (a number within 30 matches, as
  // commissioning keeps the limits up to 30 deg inside the stops), the most
  // figures, the first of equals; else the first.
  function chooseModel() {
    let best = null;
    for (let top = 0, i = 0; i < models.length; i++) {
      let score = 0;
      for (const f of models[i].figures) if (f.value !== null && f.key in values) score += (typeof f.value === 'number' ? Math.abs(values[f.key] - f.value) <= 30 : values[f.key] === f.value) ? 1 : -99;
      if (score > top) [top, best] = [score, models[i]];
    }
    best = models.find((x) => x.id === sessionStorage.model) ?? best;
    if (best) $('model').value = best.id;
  }
  function showModel() {
    const m = models.find((x) => x.id === $('model').value);
    if (!m) return;
    rows($('figures').tBodies[0], m.figures.map((f) => [f.key,
      f.value === null ? 'not published: measured' : String(f.value), f.source ?? '']));
    $('model-note').textContent = m.note;
  }
  $('model').addEventListener('change', () => {
    sessionStorage.model = $('model').value;
    showModel();
  });
  $('use-model').addEventListener('click', async () => {
    const r = await rotord.post('/api/setup/model', { model: $('model').value });
    rotord.message($('model-msg'), r.status === 200
      ? `Saved: ${r.body.changed.length} settings changed.` : r.body?.error, r.status === 200);
    await loadSettings();
    showPins();
    showEnds();
  });

  // --- 2. the wiring (setup_wiring.js): what applies here, and the boards
  let wiring = null;
  const showPins = () => wiring && wiring.show();
  $('save-pins').addEventListener('click', async () => {
    const { doc, error } = wiring.changes();
    if (error) return rotord.message($('pins-msg'), error, false);
    const r = await rotord.post('/api/settings', doc);
    rotord.message($('pins-msg'), r.status === 200 ? 'Saved (takes effect after a restart).'
      : Object.entries(r.body?.errors ?? {}).map(([k, v]) => `${k}: ${v}`).join('; ') || r.body?.error,
    r.status === 200);
    await loadSettings();
    showPins();
  });

  // --- 3. self-commissioning
  function showEnds() {
    const a = $('axis').value;
    $('ccw').value = values[a + '.min_deg'];
    $('cw').value = values[a + '.max_deg'];
    // The known bearing sets an absolute sensor's zero: offered only for one.
    const pot = values[a + '.sensor'] === 'pot';
    if (($('step-bearing').disabled = pot) && $('step').value === 'bearing') $('step').value = 'all';
    const bearing = $('step').value === 'bearing';
    $('ccw-label').hidden = $('cw-label').hidden = bearing;
    $('bearing-label').hidden = !bearing;
  }
  $('axis').addEventListener('change', showEnds);
  $('step').addEventListener('change', showEnds);
  function plot(samples) {
    if (!samples.length) return;
    const t1 = samples[samples.length - 1][0] || 1;
    const span = (i) => {
      const v = samples.map((s) => s[i]);
      const lo = Math.min(...v);
      const hi = Math.max(...v);
      return [lo, hi > lo ? hi - lo : 1];
    };
    const line = (i) => {
      const [lo, range] = span(i);
      return samples.map((s) => `${(s[0] / t1 * 400).toFixed(1)},${(155 - (s[i] - lo) / range * 150).toFixed(1)}`).join(' ');
    };
    $('pos-line').setAttribute('points', line(1));
    $('speed-line').setAttribute('points', line(2));
  }
  async function follow() {
    const r = await rotord.get('/api/commission');
    if (r.status !== 200) return;
    const c = r.body;
    const m = c.measured;
    let text = `${c.axis}: ${c.state}` + (c.state === 'running' ? ` (${c.step})` : '') +
      (c.reason ? ` - ${c.reason}` : '');
    if (m.swapped) text += '. The CW and CCW outputs are swapped: accept to swap their pins, restart, then run again.';
    if (m.fast_deg_s !== undefined) text += `. Speed ${rotord.fmt(m.fast_deg_s, 2)} deg/s, coast ${rotord.fmt(m.coast_s, 3)} s, backlash ${rotord.fmt(m.backlash_deg, 2)} deg.`;
    rotord.message($('run-state'), text, c.state !== 'aborted');
    plot(c.samples);
    rows($('proposal').tBodies[0], c.proposal.map((p) => [p.key, String(p.value), String(p.now)]));
    if (c.swap_outputs) rows($('proposal').tBodies[0], [['CW/CCW outputs', 'swapped', 'as wired']]);
    $('accept').disabled = c.state !== 'done';
    if (c.state === 'running') setTimeout(follow, 1000);
  }
  $('start').addEventListener('click', async () => {
    const body = { axis: $('axis').value, step: $('step').value };
    // Left empty: the controller says what it wants.
    for (const k of ['ccw', 'cw', 'bearing']) if ($(k).value !== '' && !$(k + '-label').hidden) body[k + '_deg'] = Number($(k).value);
    const r = await rotord.post('/api/commission', body);
    if (r.status !== 200) return rotord.message($('run-state'), r.body?.error, false);
    follow();
  });
  $('stop').addEventListener('click', async () => {
    await rotord.post('/api/stop');
    follow();
  });
  $('accept').addEventListener('click', async () => {
    const r = await rotord.post('/api/commission/accept');
    rotord.message($('accept-msg'), r.status === 200 ? `Saved: ${r.body.changed.length} settings changed.`
      : r.body?.error, r.status === 200);
    await loadSettings();
    follow();
  });

  // --- 4. the station: a Maidenhead locator gives the latitude and longitude
  $('locator').addEventListener('input', () => {
    const p = rotord.locator($('locator').value);
    if (p) { $('lat').value = p[0].toFixed(4); $('lon').value = p[1].toFixed(4); }
  });
  $('save-station').addEventListener('click', async () => {
    const doc = { 'station.lat_deg': Number($('lat').value), 'station.lon_deg': Number($('lon').value),
      'station.alt_m': Number($('alt').value || 0) };
    if ($('lat').value === '' || $('lon').value === '' || Object.values(doc).some((v) => !isFinite(v))) {
      return rotord.message($('station-msg'), 'Give a locator, or the latitude and longitude as numbers.', false);
    }
    const r = await rotord.post('/api/settings', doc);
    rotord.message($('station-msg'), r.status === 200 ? 'Saved.'
      : Object.entries(r.body?.errors ?? {}).map(([k, v]) => `${k}: ${v}`).join('; ') || r.body?.error,
    r.status === 200);
  });

  // --- 5. access
  $('save-password').addEventListener('click', async () => {
    const r = await rotord.post('/api/password', { password: $('password').value });
    rotord.message($('password-msg'), r.status === 200 ? 'Saved: log in with it from now on.'
      : r.body?.error, r.status === 200);
  });

  (async () => {
    const [m, schema] = await Promise.all([rotord.get('/api/models'), rotord.get('/api/settings/schema'),
      loadSettings()]);
    models = m.body?.models ?? [];
    wiring = rotordWiring.create({ schema: schema.body, values: () => values, box: $('pins'),
      boards: $('boards'), forSelect: $('wiring-for'), forRow: $('wiring-for-row'), note: $('pins-note') });
    for (const x of models) $('model').appendChild(Object.assign(document.createElement('option'), { value: x.id, textContent: x.name }));
    chooseModel();
    showModel();
    showPins();
    showEnds();
    // The clock's NTP (Linux) or SNTP (Pico W) state, in words.
    const setup = await rotord.get('/api/setup');
    $('clock').textContent = setup.body?.clock ?? 'not known';
    $('lat').value = values['station.lat_deg'];
    $('lon').value = values['station.lon_deg'];
    $('alt').value = values['station.alt_m'];
    follow();
  })();
})();
