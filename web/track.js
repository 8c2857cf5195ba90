// The Track page: stored objects, their next passes, a polar sky plot of the
// planned pass with the antenna's live position, and track now / at the
// next pass / STOP (docs/tracking.md, REST in docs/web_api.md#tracking).
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const msg = $('msg');
  const fmt = rotord.fmt;

  /** Sky (az, el) to the plot: zenith in the middle, the horizon at r = 90. */
  function plot(az, el) {
    const r = 90 - Math.max(0, Math.min(90, el));
    const a = (az * Math.PI) / 180;
    return [r * Math.sin(a), -r * Math.cos(a)];
  }
  /** An antenna position (el over 90 = flipped) as the sky direction it points at. */
  function skyOf(az, el) {
    if (el > 90) { az += 180; el = 180 - el; }
    return [((az % 360) + 360) % 360, el];
  }
  function place(id, az, el) {
    const c = $(id);
    if (az === null || el === null || el < 0) { c.setAttribute('visibility', 'hidden'); return; }
    const [x, y] = plot(az, el);
    c.setAttribute('cx', x.toFixed(1));
    c.setAttribute('cy', y.toFixed(1));
    c.setAttribute('visibility', 'visible');
  }

  const send = rotord.request;

  // --- objects ---------------------------------------------------------------
  let userChose = false;
  async function loadObjects() {
    const r = await rotord.get('/api/tle');
    const select = $('object');
    const chosen = select.value;
    select.textContent = '';
    const list = $('objects');
    list.textContent = '';
    const objects = r.status === 200 ? r.body.objects : [];
    for (const o of objects) {
      const opt = document.createElement('option');
      opt.value = String(o.catalog);
      opt.textContent = `${o.name} (${o.catalog})`;
      select.append(opt);
      const li = document.createElement('li');
      const age = typeof o.age_days === 'number' ? `, elements ${fmt(o.age_days, 1)} days old` : '';
      li.textContent = `${o.name} — ${o.catalog}${age} `;
      const del = document.createElement('button');
      del.type = 'button';
      del.textContent = 'Remove';
      del.addEventListener('click', async () => {
        const d = await send('DELETE', `/api/tle?object=${o.catalog}`);
        rotord.message($('tle-msg'), d.status === 200 ? `${o.name} removed` : d.body && d.body.error, d.status === 200);
        loadObjects();
      });
      li.append(del);
      list.append(li);
    }
    for (const [value, text] of [['sun', 'Sun'], ['moon', 'Moon']]) {
      const opt = document.createElement('option');
      opt.value = value;
      opt.textContent = text;
      select.append(opt);
    }
    // The user's choice stays; otherwise the first stored object.
    if (userChose && [...select.options].some((o) => o.value === chosen)) {
      select.value = chosen;
    } else {
      select.selectedIndex = 0;
    }
    loadPasses();
  }

  $('tle-file').addEventListener('change', async (e) => {
    const f = e.target.files[0];
    if (f) $('tle-text').value = await f.text();
  });
  $('tle-store').addEventListener('click', async () => {
    const r = await send('PUT', '/api/tle', $('tle-text').value, 'text/plain');
    if (r.status === 200) {
      rotord.message($('tle-msg'), `stored: ${r.body.added} new, ${r.body.replaced} replaced`, true);
      $('tle-text').value = '';
      loadObjects();
    } else {
      rotord.message($('tle-msg'), (r.body && r.body.error) || `refused (${r.status})`, false);
    }
  });

  /**
   * A refusal in words on the page, each setting it names (station.lat_deg,
   * time.trust_system_clock, ...) a link to that field of the settings page.
   */
  function problem(text) {
    msg.className = 'msg error';
    msg.replaceChildren(...String(text || 'refused').split(/\b((?:station|time|track)\.[a-z_]+)\b/)
      .map((part, i) => {
        if (i % 2 === 0) return part;
        const a = document.createElement('a');
        a.href = `settings.html#f-${part}`;
        a.textContent = part;
        return a;
      }));
  }

  // --- passes ------------------------------------------------------------------
  let passesTimer = 0;
  async function loadPasses() {
    clearTimeout(passesTimer);
    const object = $('object').value;
    const body = $('passes').tBodies[0];
    if (!object) { body.textContent = ''; return; }
    const r = await rotord.get(`/api/passes?object=${encodeURIComponent(object)}&hours=24`);
    body.textContent = '';
    if (r.status === 202) passesTimer = setTimeout(loadPasses, 1000);  // still searching
    if (r.status !== 200 && r.status !== 202) {
      problem((r.body && r.body.error) || `passes: ${r.status}`);
      return;
    }
    for (const p of r.body.passes) {
      const tr = document.createElement('tr');
      for (const v of [p.aos_utc.slice(5, 19).replace('T', ' '), p.los_utc.slice(11, 19),
        `${fmt(p.max_el_deg)}°`, `${fmt(p.aos_az_deg, 0)}°`, `${fmt(p.los_az_deg, 0)}°`]) {
        const td = document.createElement('td');
        td.textContent = v;
        tr.append(td);
      }
      body.append(tr);
    }
    if (r.status === 200 && r.body.passes.length === 0) {
      const tr = document.createElement('tr');
      const td = document.createElement('td');
      td.colSpan = 5;
      td.textContent = 'no pass in the next 24 hours';
      tr.append(td);
      body.append(tr);
    }
  }
  $('object').addEventListener('change', () => { userChose = true; loadPasses(); });

  // --- tracking ----------------------------------------------------------------
  async function start(when) {
    const object = $('object').value;
    const body = object === 'sun' || object === 'moon' ? { body: object, when } : { object, when };
    const r = await rotord.post('/api/track', body);
    if (r.status === 200) {
      rotord.message(msg, `tracking ${r.body.target.name}`, true);
      showTrack(r.body);
    } else {
      problem(r.body && r.body.error);
    }
  }
  $('track-now').addEventListener('click', () => start('now'));
  $('track-next').addEventListener('click', () => start('next'));
  $('stop').addEventListener('click', async () => {
    const r = await rotord.post('/api/stop');
    rotord.message(msg, r.status === 200 ? 'stopped' : r.body && r.body.error, r.status === 200);
    refreshTrack();
  });

  function showTrack(t) {
    $('phase').textContent = t.phase + (t.error ? ` (${t.error})` : '');
    $('target-name').textContent = t.phase === 'off' ? '–' : t.target.name;
    $('pass-times').textContent = t.pass
      ? `${t.pass.aos_utc.slice(11, 19)} / ${t.pass.los_utc.slice(11, 19)}, max el ${fmt(t.pass.max_el_deg)}°`
      : '–';
    $('plan').textContent = t.plan
      ? `${t.plan.flip ? 'flipped' : 'not flipped'}, turn ${fmt(t.plan.az_offset_deg, 0)}°${t.plan.fits ? '' : ', one unwind'}`
      : '–';
    $('utc').textContent = t.utc ? t.utc.slice(11, 19) : '–';
    const path = (t.path || []).map(([az, el]) => plot(az, el).map((v) => v.toFixed(1)).join(',')).join(' ');
    $('pass-path').setAttribute('points', path);
    place('sky-target', t.armed ? t.sky.az : null, t.armed ? t.sky.el : null);
  }
  async function refreshTrack() {
    const r = await rotord.get('/api/track');
    if (r.status === 200) showTrack(r.body);
  }
  setInterval(refreshTrack, 1000);

  rotordAccess.wire(msg);
  rotord.live((s) => {
    rotordAccess.update(s);
    if (!s.az || !s.az.valid) return;
    const el = s.el ? s.el.position_deg : 0;
    const [az, skyEl] = skyOf(s.az.position_deg, el);
    place('antenna', az, skyEl);
    $('antenna-pos').textContent = `${fmt(s.az.position_deg)}° / ${fmt(el)}°`;
  });

  loadObjects();
  refreshTrack();
})();
