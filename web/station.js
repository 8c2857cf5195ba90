// The station page: every rotord this one sees on the MQTT broker
// (GET /api/station, served by this daemon so the CSP stays 'self'), each
// as a needle on one compass and a row linking to its own panel.
'use strict';

const COLOURS = ['#d62728', '#1f77b4', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
const SVG = 'http://www.w3.org/2000/svg';

function svg(name, attrs) {
  const el = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, String(v));
  return el;
}

function cell(row, text) {
  const td = document.createElement('td');
  td.textContent = text;
  row.appendChild(td);
  return td;
}

function render(rotators) {
  const needles = document.getElementById('needles');
  const body = document.querySelector('#rotators tbody');
  needles.replaceChildren();
  body.replaceChildren();
  rotators.forEach((r, i) => {
    const colour = COLOURS[i % COLOURS.length];
    const a = ((r.az_deg % 360) + 360) % 360 * Math.PI / 180;
    const line = svg('line', {
      x1: 0, y1: 0, x2: 95 * Math.sin(a), y2: -95 * Math.cos(a),
      stroke: colour, 'stroke-width': 3, 'stroke-linecap': 'round',
      'stroke-dasharray': r.online ? 'none' : '4 4', class: 'needle',
    });
    line.dataset.prefix = r.prefix;
    const title = svg('title', {});
    title.textContent = `${r.prefix}: ${r.az_deg.toFixed(1)}°`;
    line.appendChild(title);
    needles.appendChild(line);

    const row = document.createElement('tr');
    row.dataset.prefix = r.prefix;
    const swatch = cell(row, '');
    swatch.className = 'swatch';
    const dot = swatch.appendChild(svg('svg', { width: 12, height: 12, viewBox: '0 0 12 12', 'aria-hidden': 'true' }));
    dot.appendChild(svg('circle', { cx: 6, cy: 6, r: 6, fill: colour }));
    const name = document.createElement('td');
    if (r.web) {
      const link = document.createElement('a');
      link.href = r.web;
      link.textContent = r.name || r.prefix;
      name.appendChild(link);
    } else {
      name.textContent = r.name || r.prefix;
    }
    row.appendChild(name);
    cell(row, r.prefix).className = 'prefix';
    // Where the beam points; the mechanism's azimuth beside it.
    const az = cell(row, `${r.az_deg.toFixed(1)}°`);
    if (typeof r.mech_az_deg === 'number') {
      const mech = document.createElement('span');
      mech.className = 'mech';
      mech.textContent = ` mech ${r.mech_az_deg.toFixed(1)}°`;
      az.appendChild(mech);
    }
    cell(row, r.el_deg === null ? '–' : `${r.el_deg.toFixed(1)}°`);
    cell(row, r.mode);
    cell(row, !r.online ? 'offline' : r.fault ? 'fault' : 'online');
    body.appendChild(row);
  });
}

let timer = null;

async function refresh() {
  const msg = document.getElementById('msg');
  try {
    const res = await fetch('/api/station', { cache: 'no-store' });
    if (res.status === 401) {
      location.replace('/login.html');
      return;
    }
    const doc = await res.json();
    if (!res.ok) {
      msg.textContent = doc.error || `HTTP ${res.status}`;
      render([]);
      return;
    }
    if (doc.available === false) {
      // No station on this controller (MQTT off, or a Pico W): say why once
      // and stop asking; turning MQTT on takes a restart, which reloads.
      msg.textContent = doc.reason;
      render([]);
      clearInterval(timer);
      return;
    }
    msg.textContent = doc.rotators.length ? '' : 'No rotord seen on the broker yet.';
    render(doc.rotators);
  } catch (e) {
    msg.textContent = `Cannot reach rotord: ${e.message}`;
  }
}

timer = setInterval(refresh, 2000);
refresh();
