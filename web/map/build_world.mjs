// node build_world.mjs <countries-110m.json> <out.js>
// Converts world-atlas' TopoJSON (Natural Earth 1:110m) into the map page's
// compact form at build time (core/web/world_map.cmake): only the arcs it
// draws (coastlines: the land's outline; borders: the countries' arcs that
// are not coast), each a run of delta-encoded quantized points, as one
// string. The browser (web/map_draw.js) sums the deltas and applies the
// transform; nothing is fetched at run time.
import { readFileSync, writeFileSync } from 'node:fs';

const [input, output] = process.argv.slice(2);
const topo = JSON.parse(readFileSync(input, 'utf8'));

function arcsOf(geometry, into) {
  const walk = (a) => (Array.isArray(a) ? a.forEach(walk) : into.add(a < 0 ? ~a : a));
  if (geometry.type === 'GeometryCollection') geometry.geometries.forEach((g) => arcsOf(g, into));
  else if (geometry.arcs) walk(geometry.arcs);
  return into;
}

const coast = arcsOf(topo.objects.land, new Set());
const all = arcsOf(topo.objects.countries, new Set());
const borders = [...all].filter((i) => !coast.has(i));
// The 1:110m data on a grid of 0.0036 x 0.0017 deg, coarsened by QUANT (about
// 0.014 deg, far below a pixel of a whole-Earth map): fewer digits, and points
// that fall together are dropped.
const QUANT = 4;
function requantize(arc) {
  let x = 0, y = 0, px = 0, py = 0;
  const out = [];
  arc.forEach(([dx, dy], n) => {
    x += dx;
    y += dy;
    const qx = Math.round(x / QUANT), qy = Math.round(y / QUANT);
    if (n > 0 && qx === px && qy === py && n < arc.length - 1) return;
    out.push(qx - px, qy - py);
    px = qx;
    py = qy;
  });
  return out;
}
const encode = (indices) =>
  [...indices].sort((a, b) => a - b).map((i) => requantize(topo.arcs[i]).join(',')).join(';');

const scale = topo.transform.scale.map((s) => s * QUANT);
const { translate } = topo.transform;
const text =
  '// Generated at build time by web/map/build_world.mjs from world-atlas ' +
  '(Natural Earth 1:110m, public domain). Do not edit.\n' +
  `const WORLD = {scale: ${JSON.stringify(scale)}, translate: ${JSON.stringify(translate)},\n` +
  `coast: '${encode(coast)}',\nborders: '${encode(borders)}'};\n`;
writeFileSync(output, text);
