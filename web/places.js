// Where the beam points (issue 26), shared by the control and map pages:
// turn to a locator or a position (bearing and distance shown first), the
// presets, and the map's pick panel. Each part wires itself only when its
// elements are on the page.
'use strict';

const rotordPlaces = (() => {
  const $ = (id) => document.getElementById(id);
  const fmt = rotord.fmt;

  /** "52.5 13.4", "52.5,13.4" or a locator, into GET/POST /api/place's members. */
  function parse(text) {
    const m = text.trim().match(/^(-?\d+(?:\.\d*)?)\s*[, ]\s*(-?\d+(?:\.\d*)?)$/);
    return m ? { lat: Number(m[1]), lon: Number(m[2]) } : { locator: text.trim() };
  }
  const query = (place, path) =>
    new URLSearchParams(Object.assign({}, place, { path })).toString();
  const describe = (r) => `${fmt(r.bearing_deg)}°, ${fmt(r.distance_km, 0)} km (${r.path} path)`;

  async function preview(place, path) {
    const r = await rotord.get('/api/place?' + query(place, path));
    if (r.status !== 200) return { error: (r.body && r.body.error) || `error ${r.status}` };
    return r.body;
  }
  async function turn(place, path, msg) {
    const r = await rotord.post('/api/place', Object.assign({}, place, { path }));
    if (r.status === 200) rotord.message(msg, 'turning to ' + describe(r.body), true);
    else rotord.message(msg, (r.body && r.body.error) || `error ${r.status}`, false);
    return r;
  }

  function wirePlace(msg) {
    const form = $('place-form');
    if (!form) return;
    const out = $('place-out');
    const current = () => [parse($('place-text').value), $('place-long').checked ? 'long' : 'short'];
    async function show() {
      const [place, path] = current();
      const r = await preview(place, path);
      out.textContent = r.error ? r.error : describe(r) + (r.reachable ? '' : ' – ' + r.why);
      out.className = 'msg ' + (r.error || !r.reachable ? 'error' : 'ok');
    }
    $('place-text').addEventListener('change', show);
    $('place-long').addEventListener('change', show);
    $('place-show').addEventListener('click', show);
    form.addEventListener('submit', (e) => {
      e.preventDefault();
      const [place, path] = current();
      turn(place, path, msg);
    });
  }

  function wirePresets(msg) {
    const list = $('presets');
    if (!list) return;
    async function load() {
      const r = await rotord.get('/api/presets');
      if (r.status !== 200) return;
      list.replaceChildren();
      for (const p of r.body.presets) {
        const item = document.createElement('span');
        item.className = 'preset';
        const go = document.createElement('button');
        go.type = 'button';
        go.dataset.name = p.name;
        go.textContent = `${p.name} ${fmt(p.az_deg, 0)}°${p.long_path ? ' LP' : ''}`;
        go.addEventListener('click', async () => {
          const t = await rotord.post('/api/preset', { name: p.name });
          if (t.status === 200) rotord.message(msg, `turning to ${p.name}, ${fmt(p.az_deg)}°`, true);
          else rotord.message(msg, (t.body && t.body.error) || `error ${t.status}`, false);
        });
        const del = document.createElement('button');
        del.type = 'button';
        del.className = 'preset-delete';
        del.title = `delete ${p.name}`;
        del.textContent = '×';
        del.addEventListener('click', async () => {
          const d = await rotord.post('/api/presets/delete', { name: p.name });
          if (d.status !== 200) rotord.message(msg, (d.body && d.body.error) || `error ${d.status}`, false);
          load();
        });
        item.append(go, del);
        list.appendChild(item);
      }
    }
    $('preset-form').addEventListener('submit', async (e) => {
      e.preventDefault();
      const r = await rotord.post('/api/presets', {
        name: $('preset-name').value.trim(),
        az: Number($('preset-az').value),
        long_path: $('preset-long').checked,
      });
      if (r.status === 200) rotord.message(msg, 'preset saved', true);
      else rotord.message(msg, (r.body && r.body.error) || `error ${r.status}`, false);
      load();
    });
    load();
  }

  /**
   * The map in `svg`, its pick panel (#pick-out, #pick-short, #pick-long) and
   * the sky (refreshed each minute). Returns update(status) for the beam.
   */
  function wireMap(svg, msg) {
    let picked = null;
    const out = $('pick-out');
    const map = rotordMap.create(svg, async (place) => {
      picked = { lat: Number(place.lat.toFixed(5)), lon: Number(place.lon.toFixed(5)) };
      const [s, l] = await Promise.all([preview(picked, 'short'), preview(picked, 'long')]);
      if (s.error) { out.textContent = s.error; return; }
      out.textContent = `${fmt(picked.lat, 2)}, ${fmt(picked.lon, 2)}: ${describe(s)}` +
        `${s.reachable ? '' : ' – ' + s.why}; long path ${fmt(l.bearing_deg)}°, ${fmt(l.distance_km, 0)} km`;
      $('pick-short').disabled = !s.reachable;
      $('pick-long').disabled = !l.reachable;
      $('pick-actions').hidden = false;
    });
    $('pick-short').addEventListener('click', () => picked && turn(picked, 'short', msg));
    $('pick-long').addEventListener('click', () => picked && turn(picked, 'long', msg));
    async function sky() {
      const r = await rotord.get('/api/sky');
      if (r.status !== 200) return;
      map.setStation(r.body.station.lat_deg, r.body.station.lon_deg);
      map.setSky(r.body);
      svg.dataset.ready = '1';
    }
    sky();
    setInterval(sky, 60000);
    return (s) => {
      if (!s.beam) return map.setBeam(null, null);
      map.setBeam(s.beam.az_deg, s.beam.target_az_deg);
    };
  }

  return { wirePlace, wirePresets, wireMap, parse };
})();
