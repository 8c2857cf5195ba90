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
  function showModel() {
    const m = models.find((x) => x.id === $('model').value);
    if (!m) return;
    rows($('figures').tBodies[0], m.figures.map((f) => [f.key,
      f.value === null ? 'not published: measured' : String(f.value), f.source ?? '']));
    $('model-note').textContent = m.note;
  }
  $('model').addEventListener('change', showModel);
  $('use-model').addEventListener('click', async () => {
    const r = await rotord.post('/api/setup/model', { model: $('model').value });
    rotord.message($('model-msg'), r.status === 200
      ? `Saved: ${r.body.changed.length} settings changed.` : r.body?.error, r.status === 200);
    await loadSettings();
    showPins();
    showEnds();
  });

  // --- 2. the wiring: only what this drive, sensor and axes use
  function wiringKeys() {
    const keys = [];
    const axes = [['az', 'cw', 'ccw', 'az.', 'l1', 'l2']];
    if (values['el.enabled']) axes.push(['el', 'up', 'down', 'el.', 'limit_up', 'limit_down']);
    for (const [a, fwd, rev, p, l1, l2] of axes) {
      const drive = values[p + 'drive'];
      const both = (name) => keys.push(`pins.${a}_${name}`, `gpiod.${a}_${name}`);
      if (drive === 'hbridge') keys.push(`pins.${a}_pwm_${fwd}`, `pins.${a}_pwm_${rev}`);
      else { both(fwd); both(rev); }
      if (drive === 'relay_two_speed' || drive === 'relay_voltage_select') both('speed');
      if (a === 'az' && values['az.has_brake']) both('brake');
      const sensor = values[p + 'sensor'];
      if (sensor === 'pot') keys.push(`pins.${a}_pot`);
      if (sensor === 'ma3') both('ma3');
      both(l1);
      both(l2);
    }
    return keys.filter((k) => k in values);
  }
  function showPins() {
    const box = $('pins');
    box.textContent = '';
    for (const key of wiringKeys()) {
      const label = document.createElement('label');
      label.textContent = (key.startsWith('pins.') ? 'Pico W ' : 'Raspberry Pi ') + key + ' ';
      const input = document.createElement('input');
      Object.assign(input, { type: 'number', step: '1', value: values[key], id: 'pin-' + key });
      input.dataset.key = key;
      label.appendChild(input);
      box.appendChild(label);
    }
  }
  $('save-pins').addEventListener('click', async () => {
    const doc = {};
    for (const input of $('pins').querySelectorAll('input')) {
      const v = Number(input.value);
      if (input.value.trim() === '' || !Number.isInteger(v)) {
        return rotord.message($('pins-msg'), `${input.dataset.key}: a whole number, -1 = not wired`, false);
      }
      if (v !== values[input.dataset.key]) doc[input.dataset.key] = v;
    }
    const r = await rotord.post('/api/settings', doc);
    rotord.message($('pins-msg'), r.status === 200 ? 'Saved (takes effect after a restart).'
      : Object.entries(r.body?.errors ?? {}).map(([k, v]) => `${k}: ${v}`).join('; ') || r.body?.error,
    r.status === 200);
    await loadSettings();
  });

  // --- 3. self-commissioning
  function showEnds() {
    const a = $('axis').value;
    $('ccw').value = values[a + '.min_deg'];
    $('cw').value = values[a + '.max_deg'];
  }
  $('axis').addEventListener('change', showEnds);
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
    if ($('ccw').value !== '') body.ccw_deg = Number($('ccw').value);
    if ($('cw').value !== '') body.cw_deg = Number($('cw').value);
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
  function locatorToLatLon(loc) {
    const s = loc.trim().toUpperCase();
    if (!/^[A-R]{2}([0-9]{2}([A-X]{2}([0-9]{2})?)?)?$/.test(s)) return null;
    let lon = (s.charCodeAt(0) - 65) * 20 - 180;
    let lat = (s.charCodeAt(1) - 65) * 10 - 90;
    let w = 20;
    let h = 10;
    if (s.length >= 4) { w = 2; h = 1; lon += Number(s[2]) * 2; lat += Number(s[3]); }
    if (s.length >= 6) { w /= 24; h /= 24; lon += (s.charCodeAt(4) - 65) * w; lat += (s.charCodeAt(5) - 65) * h; }
    if (s.length >= 8) { w /= 10; h /= 10; lon += Number(s[6]) * w; lat += Number(s[7]) * h; }
    return [lat + h / 2, lon + w / 2];  // the square's centre
  }
  $('locator').addEventListener('input', () => {
    const p = locatorToLatLon($('locator').value);
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
    const [m] = await Promise.all([rotord.get('/api/models'), loadSettings()]);
    models = m.body?.models ?? [];
    for (const x of models) $('model').appendChild(Object.assign(document.createElement('option'), { value: x.id, textContent: x.name }));
    showModel();
    showPins();
    showEnds();
    $('lat').value = values['station.lat_deg'];
    $('lon').value = values['station.lon_deg'];
    $('alt').value = values['station.alt_m'];
    follow();
  })();
})();
