// The control page: compass rose, readouts, go-to, hold-to-move, park, STOP.
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const SVGNS = 'http://www.w3.org/2000/svg';
  const msg = $('msg');
  const R = 100;
  let last = null;
  let drawQueued = false;

  // --- drawing ---------------------------------------------------------------
  const polar = (deg, r) => {
    const a = (deg * Math.PI) / 180;
    return [r * Math.sin(a), -r * Math.cos(a)];
  };
  /** A filled annular sector from compass angle a0 clockwise to a1 (degrees). */
  function sector(a0, a1, r0, r1) {
    let span = a1 - a0;
    if (span <= 0) return '';
    if (span >= 360) span = 359.99;
    const large = span > 180 ? 1 : 0;
    const [x0, y0] = polar(a0, r1);
    const [x1, y1] = polar(a0 + span, r1);
    const [x2, y2] = polar(a0 + span, r0);
    const [x3, y3] = polar(a0, r0);
    return `M${x0} ${y0}A${r1} ${r1} 0 ${large} 1 ${x1} ${y1}L${x2} ${y2}` +
      `A${r0} ${r0} 0 ${large} 0 ${x3} ${y3}Z`;
  }

  (function ticks() {
    const g = $('ticks');
    for (let d = 0; d < 360; d += 10) {
      const major = d % 30 === 0;
      const [x1, y1] = polar(d, major ? 88 : 93);
      const [x2, y2] = polar(d, 100);
      const line = document.createElementNS(SVGNS, 'line');
      line.setAttribute('class', major ? 'tick major' : 'tick');
      line.setAttribute('x1', x1); line.setAttribute('y1', y1);
      line.setAttribute('x2', x2); line.setAttribute('y2', y2);
      g.appendChild(line);
      if (major) {
        const [tx, ty] = polar(d, 79);
        const t = document.createElementNS(SVGNS, 'text');
        t.setAttribute('class', 'rose-label');
        t.setAttribute('x', tx); t.setAttribute('y', ty);
        t.textContent = { 0: 'N', 90: 'E', 180: 'S', 270: 'W' }[d] || String(d);
        g.appendChild(t);
      }
    }
  })();

  const wrap = (d) => ((d % 360) + 360) % 360;

  function draw() {
    drawQueued = false;
    const s = last;
    if (!s) return;
    const l = s.limits;
    document.body.classList.toggle('no-el', !l.has_el);
    // Travel: the overlap (reachable twice) and the unreachable part.
    const travel = l.az_max - l.az_min;
    $('overlap').setAttribute('d', !l.az_continuous && travel > 360
      ? sector(wrap(l.az_min + 360), wrap(l.az_min + 360) + (travel - 360), 60, R) : '');
    $('blocked').setAttribute('d', !l.az_continuous && travel < 360
      ? sector(wrap(l.az_max), wrap(l.az_max) + (360 - travel), 60, R) : '');
    for (const [id, v] of [['limit-min', l.az_min], ['limit-max', l.az_max]]) {
      $(id).setAttribute('transform', `rotate(${wrap(v)})`);
      $(id).setAttribute('visibility', l.az_continuous ? 'hidden' : 'visible');
    }
    const az = s.az.position_deg;
    // Where the beam points (after a flip over the zenith) is the main figure.
    const beamAz = s.beam ? s.beam.az_deg : az;
    $('needle').setAttribute('transform', `rotate(${wrap(beamAz)})`);
    $('beam').setAttribute('d', sector(wrap(beamAz) - 15, wrap(beamAz) + 15, 0, 98));
    const t = s.az.target_deg;
    const beamTarget = s.beam && s.beam.target_az_deg !== null ? s.beam.target_az_deg : t;
    $('target').setAttribute('visibility', t === null ? 'hidden' : 'visible');
    if (t !== null) $('target').setAttribute('transform', `rotate(${wrap(beamTarget)})`);

    $('az').textContent = rotord.fmt(wrap(beamAz)) + '°';
    $('az-mech').textContent = `mechanism ${rotord.fmt(az)}°`;
    $('az-mech').title = `unwrapped ${rotord.fmt(az)}°, raw ${rotord.fmt(s.az.raw, 0)} ${s.az.raw_unit}`;
    const targets = [];
    if (t !== null) targets.push('az ' + rotord.fmt(t));
    if (s.el) {
      $('el').textContent = rotord.fmt(s.beam && s.beam.el_deg !== null ? s.beam.el_deg : s.el.position_deg) + '°';
      $('el-mech').textContent = `mechanism ${rotord.fmt(s.el.position_deg)}°`;
      $('el-needle').setAttribute('transform', `rotate(${-s.el.position_deg} 100 0)`);
      const et = s.el.target_deg;
      $('el-target').setAttribute('visibility', et === null ? 'hidden' : 'visible');
      if (et !== null) {
        $('el-target').setAttribute('transform', `rotate(${-et} 100 0)`);
        targets.push('el ' + rotord.fmt(et));
      }
      // Outside the travel: above el_max and below el_min (on the 0..180 arc).
      const above = Math.max(0, l.el_max), below = Math.min(180, l.el_min);
      $('el-blocked').setAttribute('d', (above < 180 ? elevSector(above, 180) : '') +
        (below > 0 ? elevSector(0, below) : ''));
    }
    $('tgt').textContent = targets.length ? targets.join(', ') : '–';
    const axes = s.el ? [['az', s.az], ['el', s.el]] : [['az', s.az]];
    $('state').textContent = s.mode + ' · ' + axes.map(([n, a]) => `${n} ${a.state}`).join(', ');
    // A pass recognised in a client's go-tos (docs/tracking.md), or how the last one ended.
    const r = s.recognised;
    $('recognised-row').hidden = !r;
    if (r) {
      $('recognised').textContent = r.active
        ? `following ${r.object} (recognised in a client's go-tos since ${r.since_utc})`
        : `${r.object}: recognition ended (${r.ended}) at ${r.ended_utc}`;
    }
    const faults = axes.filter(([, a]) => a.fault !== 'none').map(([n, a]) => `${n}: ${a.fault}`);
    $('faults').hidden = faults.length === 0;
    $('fault-text').textContent = faults.length ? 'Fault ' + faults.join(', ') : '';
    // Looked after unattended (docs/care.md): slips and rejected readings.
    $('care').textContent = axes.map(([n, a]) => `${n} ${a.slips} slip${a.slips === 1 ? '' : 's'}` +
      (a.slipping ? ' (slipping now)' : '') + `, ${a.readings_rejected} rejected`).join(' · ');
    // Wind stow (docs/care.md): shown once a source is configured.
    const wd = s.wind;
    $('wind-row').hidden = !wd || wd.source === 'off';
    if (wd && wd.source !== 'off') {
      const speed = wd.speed_mps === null ? 'no reading yet' : `${wd.speed_mps.toFixed(1)} m/s`;
      const dir = wd.dir_deg === null ? '' : ` from ${Math.round(wd.dir_deg)}°`;
      const what = {
        calm: `calm (stows at ${wd.stow_mps} m/s)`,
        rising: `above ${wd.stow_mps} m/s: stowing if it holds`,
        stowed: `STOWED at ${wd.stow_az_deg.toFixed(0)}°: moves refused until calm ` +
          `(${Math.ceil(wd.calm_left_s / 60)} min below ${wd.calm_mps} m/s)` +
          (wd.stopped_by_operator ? '; stopped by STOP' : ''),
        override: `stow overridden for ${Math.ceil(wd.override_left_s / 60)} min more`,
      }[wd.state] || wd.state;
      const bad = Object.values(wd.rejected).reduce((x, y) => x + y, 0);
      $('wind').textContent = `${speed}${dir}, ${what}, ${wd.stows} stow${wd.stows === 1 ? '' : 's'}` +
        (bad ? `, ${bad} readings ignored` : '');
      $('wind-override').hidden = wd.state !== 'stowed';
      $('wind-end-override').hidden = wd.state !== 'override';
    }
    // The wear odometer (docs/care.md), and a go-to the starts ceiling holds.
    const o = s.odometer;
    if (o) {
      $('wear').textContent = axes.filter(([n]) => o[n]).map(([n]) => {
        const w = o[n];
        return `${n} ${w.starts} starts, ${(w.run_s / 3600).toFixed(1)} h, ${w.turned_deg}°, ` +
          `${w.relay_switchings} relay, ${w.faults_total} faults` +
          (w.start_held ? ` (starts ceiling: waiting, tolerance ${w.widened_tolerance_deg.toFixed(1)}°)` : '');
      }).join(' · ') + (o.reset_utc ? ` · since ${o.reset_utc.slice(0, 10)}` : '');
    }
    if (document.activeElement !== $('speed')) $('speed').value = s.speed_pct;
    // A relay drive has one speed: the slider would move and change nothing.
    const oneSpeed = s.speed_applies === false;
    $('speed').disabled = oneSpeed;
    $('speed-note').hidden = !oneSpeed;
    $('speed-out').textContent = oneSpeed ? '–' : s.speed_pct + '%';
  }
  function elevSector(e0, e1) {
    const p = (e, r) => [100 + r * Math.cos((e * Math.PI) / 180), -r * Math.sin((e * Math.PI) / 180)];
    const [x0, y0] = p(e0, 100), [x1, y1] = p(e1, 100);
    return `M100 0L${x0} ${y0}A100 100 0 0 0 ${x1} ${y1}Z`;
  }

  // hold_ms is wall time on rotord's side too (its dead-man runs on the
  // transport's clock), whatever --speedup does to the simulation.
  const HOLD_WALL_MS = 700;  // motion stops at most this long after the last renewal
  const RENEW_MS = 200;

  // --- commands ----------------------------------------------------------------
  async function command(path, body, okText) {
    const r = await rotord.post(path, body);
    if (r.status === 200 || r.status === 202) rotord.message(msg, okText || '', true);
    else rotord.message(msg, (r.body && r.body.error) || `error ${r.status}`, false);
    return r;
  }

  let holding = null;  // {dir, timer, button}
  function startHold(dir, button) {
    if (holding && holding.dir === dir) return;
    stopHold(false);
    const send = () => rotord.post('/api/move', { dir, speed: Number($('speed').value) || undefined,
      hold_ms: HOLD_WALL_MS }).then((r) => {
      if (r.status !== 200 && holding && holding.dir === dir) {
        rotord.message(msg, (r.body && r.body.error) || `error ${r.status}`, false);
        stopHold(true);
      }
    });
    holding = { dir, button, timer: setInterval(send, RENEW_MS) };
    if (button) button.classList.add('held');
    rotord.message(msg, '');
    send();
  }
  function stopHold(sendStop) {
    if (!holding) return;
    clearInterval(holding.timer);
    if (holding.button) holding.button.classList.remove('held');
    const axis = holding.dir === 'up' || holding.dir === 'down' ? 'el' : 'az';
    holding = null;
    if (sendStop !== false) rotord.post('/api/move', { axis, dir: 'stop' });
  }

  for (const b of document.querySelectorAll('.hold button')) {
    b.addEventListener('pointerdown', (e) => {
      e.preventDefault();
      b.setPointerCapture(e.pointerId);
      startHold(b.dataset.dir, b);
    });
    for (const ev of ['pointerup', 'pointercancel', 'lostpointercapture']) {
      b.addEventListener(ev, () => { if (holding && holding.button === b) stopHold(); });
    }
    b.addEventListener('contextmenu', (e) => e.preventDefault());  // long-press menu on phones
  }
  // Anything that takes the page away stops a held move at once.
  window.addEventListener('blur', () => stopHold());
  window.addEventListener('pagehide', () => stopHold());
  document.addEventListener('visibilitychange', () => { if (document.hidden) stopHold(); });

  const keys = { ArrowLeft: 'ccw', ArrowRight: 'cw', ArrowUp: 'up', ArrowDown: 'down' };
  const typing = () => ['INPUT', 'SELECT', 'TEXTAREA'].includes(document.activeElement.tagName);
  document.addEventListener('keydown', (e) => {
    if (typing()) return;
    if (e.key === 'Escape' || e.key === ' ') {
      e.preventDefault();
      stopHold(false);
      command('/api/stop');
      return;
    }
    const dir = keys[e.key];
    if (!dir || (last && !last.el && (dir === 'up' || dir === 'down'))) return;
    e.preventDefault();
    if (!e.repeat) startHold(dir, document.querySelector(`.hold [data-dir="${dir}"]`));
  });
  document.addEventListener('keyup', (e) => {
    if (keys[e.key] && holding && holding.dir === keys[e.key]) stopHold();
  });

  $('stop').addEventListener('click', () => { stopHold(false); command('/api/stop', {}, 'stopped'); });
  $('park').addEventListener('click', () => command('/api/park', {}, 'parking'));
  $('wind-override').addEventListener('click',
    () => command('/api/wind/override', {}, 'stow overridden: moves obeyed for wind.override_min'));
  $('wind-end-override').addEventListener('click',
    () => command('/api/wind/override', { end: true }, 'stowing again'));
  $('clear').addEventListener('click', () => command('/api/reset', {}, 'faults cleared'));
  $('speed').addEventListener('change', () => command('/api/speed', { speed_pct: Number($('speed').value) }));
  $('speed').addEventListener('input', () => { $('speed-out').textContent = $('speed').value + '%'; });
  $('goto').addEventListener('submit', (e) => {
    e.preventDefault();
    const body = {};
    const az = $('goto-az').value.trim();
    const el = $('goto-el').value.trim();
    if (az !== '') body.az = Number(az);
    if (el !== '' && last && last.el) body.el = Number(el);
    if (!Object.keys(body).length) return rotord.message(msg, 'enter an azimuth or elevation', false);
    command('/api/goto', body, 'going');
  });
  $('rose').addEventListener('click', (e) => {
    const svg = $('rose');
    const pt = svg.createSVGPoint();
    pt.x = e.clientX; pt.y = e.clientY;
    const p = pt.matrixTransform(svg.getScreenCTM().inverse());
    if (Math.hypot(p.x, p.y) > 112) return;
    const az = Math.round(wrap((Math.atan2(p.x, -p.y) * 180) / Math.PI));
    $('goto-az').value = az;
    command('/api/goto', { az }, `going to ${az}°`);
  });

  rotordPlaces.wirePlace(msg);
  rotordPlaces.wirePresets(msg);
  // The map below the controls on a desktop (its coastlines are loaded
  // only there: a phone has the map page).
  let updateMap = null;
  if (window.matchMedia('(min-width: 1000px)').matches) {
    const load = (src) => new Promise((resolve) => {
      const script = document.createElement('script');
      script.src = src;
      script.onload = resolve;
      document.body.appendChild(script);
    });
    load('/world.js').then(() => load('/map_draw.js')).then(() => {
      updateMap = rotordPlaces.wireMap($('map'), msg);
      if (last) updateMap(last);
    });
  }

  rotordAccess.wire(msg);
  rotord.live((s) => {
    last = s;
    if (updateMap) updateMap(s);
    rotordAccess.update(s);
    if (!drawQueued) { drawQueued = true; requestAnimationFrame(draw); }
  });
  rotord.get('/api/status').then((r) => { if (r.status === 200 && !last) { last = r.body; draw(); } });
  // Nothing saved yet: offer the set-up page.
  rotord.get('/api/setup').then((r) => { if (r.status === 200 && !r.body.configured) $('setup-offer').hidden = false; });
})();
