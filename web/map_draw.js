// The map (issue 26): an azimuthal equidistant projection centred on the
// station, so a straight line from the centre is a great circle and its
// angle is the bearing. Coastlines and borders from world.js (Natural Earth
// via world-atlas, converted at build time); the Sun, the Moon and the grey
// line from GET /api/sky (the core's own Sun and Moon). Plain SVG, no library.
'use strict';

const rotordMap = (() => {
  const SVGNS = 'http://www.w3.org/2000/svg';
  const D = Math.PI / 180;
  const EARTH_KM = 6371.0088;
  const R = 100;  // the antipode's circle, in SVG units
  const K = R / Math.PI;  // SVG units per radian of great-circle angle

  /** world.js' arcs as [lon, lat] runs (once). */
  let arcs = null;
  function decode(text) {
    const { scale, translate } = WORLD;
    return text.split(';').map((arc) => {
      const v = arc.split(',').map(Number);
      const out = new Float64Array(v.length);
      let x = 0, y = 0;
      for (let i = 0; i < v.length; i += 2) {
        x += v[i]; y += v[i + 1];
        out[i] = x * scale[0] + translate[0];
        out[i + 1] = y * scale[1] + translate[1];
      }
      return out;
    });
  }

  /** Great-circle angle (rad) and bearing (rad) from (lat0, lon0) to (lat, lon). */
  function polar(lat0, lon0, lat, lon) {
    const p1 = lat0 * D, p2 = lat * D, dl = (lon - lon0) * D;
    const cosc = Math.sin(p1) * Math.sin(p2) + Math.cos(p1) * Math.cos(p2) * Math.cos(dl);
    const c = Math.acos(Math.max(-1, Math.min(1, cosc)));
    const az = Math.atan2(Math.sin(dl) * Math.cos(p2),
      Math.cos(p1) * Math.sin(p2) - Math.sin(p1) * Math.cos(p2) * Math.cos(dl));
    return [c, az];
  }
  function project(lat0, lon0, lat, lon) {
    const [c, az] = polar(lat0, lon0, lat, lon);
    return [K * c * Math.sin(az), -K * c * Math.cos(az)];
  }
  /** The point at angle c (rad) along bearing az (rad) from (lat0, lon0). */
  function destination(lat0, lon0, c, az) {
    const p1 = lat0 * D;
    const lat = Math.asin(Math.sin(p1) * Math.cos(c) + Math.cos(p1) * Math.sin(c) * Math.cos(az));
    const lon = lon0 * D + Math.atan2(Math.sin(az) * Math.sin(c) * Math.cos(p1),
      Math.cos(c) - Math.sin(p1) * Math.sin(lat));
    return [lat / D, ((lon / D + 540) % 360) - 180];
  }

  function el(name, attrs, parent) {
    const e = document.createElementNS(SVGNS, name);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
    if (parent) parent.appendChild(e);
    return e;
  }

  /** A path through projected points, broken where it jumps across the antipode. */
  function pathOf(points, lat0, lon0, closed) {
    let d = '', prev = null;
    for (let i = 0; i < points.length; i += 2) {
      const [x, y] = project(lat0, lon0, points[i + 1], points[i]);
      const jump = prev && Math.hypot(x - prev[0], y - prev[1]) > 25;
      d += (prev === null || jump ? 'M' : 'L') + x.toFixed(1) + ' ' + y.toFixed(1);
      prev = [x, y];
    }
    return closed && d ? d + 'Z' : d;
  }

  function sector(az0, az1) {
    const p = (a) => [R * Math.sin(a * D), -R * Math.cos(a * D)];
    const [x0, y0] = p(az0), [x1, y1] = p(az1);
    return `M0 0L${x0} ${y0}A${R} ${R} 0 ${az1 - az0 > 180 ? 1 : 0} 1 ${x1} ${y1}Z`;
  }

  /**
   * Draws into `svg` (an empty <svg>). onPick({lat, lon}) when a point inside
   * the Earth is clicked or tapped. Returns {setStation, setSky, setBeam}.
   */
  function create(svg, onPick) {
    if (!arcs) arcs = { coast: decode(WORLD.coast), borders: decode(WORLD.borders) };
    svg.setAttribute('viewBox', '-108 -108 216 216');
    svg.classList.add('map');
    el('circle', { r: R, class: 'map-sea' }, svg);
    const borders = el('path', { class: 'map-border' }, svg);
    const coast = el('path', { class: 'map-coast' }, svg);
    const rings = el('g', { class: 'map-ring' }, svg);
    for (const km of [5000, 10000, 15000]) el('circle', { r: (K * km) / EARTH_KM }, rings);
    const grey = el('path', { class: 'map-grey' }, svg);
    const wedge = el('path', { class: 'map-wedge' }, svg);
    const target = el('line', { class: 'map-target', x1: 0, y1: 0, x2: 0, y2: -R, visibility: 'hidden' }, svg);
    const beam = el('line', { class: 'map-beam', x1: 0, y1: 0, x2: 0, y2: -R }, svg);
    const pick = el('circle', { class: 'map-pick', r: 2.2, visibility: 'hidden' }, svg);
    const sun = el('circle', { class: 'map-sun', r: 3.2, visibility: 'hidden' }, svg);
    const moon = el('circle', { class: 'map-moon', r: 2.6, visibility: 'hidden' }, svg);
    el('circle', { class: 'map-station', r: 2 }, svg);
    for (const [a, t] of [[0, 'N'], [90, 'E'], [180, 'S'], [270, 'W']]) {
      const l = el('text', { class: 'map-label', x: 104 * Math.sin(a * D), y: -104 * Math.cos(a * D) }, svg);
      l.textContent = t;
    }
    const state = { lat: 0, lon: 0, sky: null, beamwidth: 60 };

    function drawSky() {
      const s = state.sky;
      for (const [mark, body] of [[sun, s && s.sun], [moon, s && s.moon]]) {
        mark.setAttribute('visibility', body ? 'visible' : 'hidden');
        if (!body) continue;
        const [x, y] = project(state.lat, state.lon, body.lat_deg, body.lon_deg);
        mark.setAttribute('cx', x); mark.setAttribute('cy', y);
      }
      // The grey line: every point 90 deg from the subsolar point.
      if (!s || !s.sun) { grey.setAttribute('d', ''); return; }
      const pts = [];
      for (let b = 0; b <= 360; b += 2) {
        const [lat, lon] = destination(s.sun.lat_deg, s.sun.lon_deg, Math.PI / 2, b * D);
        pts.push(lon, lat);
      }
      grey.setAttribute('d', pathOf(pts, state.lat, state.lon, false));
    }

    // Where the pointer went down: a pointer event has fractional pixels, a
    // click whole ones (half a pixel is 0.2 deg of bearing on a phone).
    let down = null;
    svg.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
    svg.addEventListener('click', (e) => {
      const near = down && Math.abs(down[0] - e.clientX) <= 1 && Math.abs(down[1] - e.clientY) <= 1;
      const pt = svg.createSVGPoint();
      [pt.x, pt.y] = near ? down : [e.clientX, e.clientY];
      down = null;
      const p = pt.matrixTransform(svg.getScreenCTM().inverse());
      const c = Math.hypot(p.x, p.y) / K;
      if (c > Math.PI) return;
      const [lat, lon] = destination(state.lat, state.lon, c, Math.atan2(p.x, -p.y));
      pick.setAttribute('cx', p.x); pick.setAttribute('cy', p.y);
      pick.setAttribute('visibility', 'visible');
      onPick({ lat, lon });
    });

    return {
      setStation(lat, lon) {
        if (lat === state.lat && lon === state.lon && coast.getAttribute('d')) return;
        state.lat = lat; state.lon = lon;
        svg.dataset.centre = `${lat} ${lon}`;
        coast.setAttribute('d', arcs.coast.map((a) => pathOf(a, lat, lon, false)).join(''));
        borders.setAttribute('d', arcs.borders.map((a) => pathOf(a, lat, lon, false)).join(''));
        pick.setAttribute('visibility', 'hidden');
        drawSky();
      },
      setSky(sky) {
        state.sky = sky;
        if (sky && typeof sky.beamwidth_deg === 'number') state.beamwidth = sky.beamwidth_deg;
        drawSky();
      },
      /** The beam's compass heading now and where it is going (null: none). */
      setBeam(az, targetAz) {
        const show = typeof az === 'number';
        beam.setAttribute('visibility', show ? 'visible' : 'hidden');
        wedge.setAttribute('d', show ? sector(az - state.beamwidth / 2, az + state.beamwidth / 2) : '');
        if (show) beam.setAttribute('transform', `rotate(${az})`);
        target.setAttribute('visibility', typeof targetAz === 'number' ? 'visible' : 'hidden');
        if (typeof targetAz === 'number') target.setAttribute('transform', `rotate(${targetAz})`);
      },
    };
  }

  return { create, project, destination, EARTH_KM };
})();
