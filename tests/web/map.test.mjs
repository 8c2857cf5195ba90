// Where the beam points (issue 26) in the real browser (Debian's chromium,
// playwright-core) at a phone's 390x844 and a desktop's 1280x900: the map
// centred on the station for three locators, a click on a city turning the
// antenna to the bearing this test computes itself (its own Maidenhead and
// great-circle code, not the core's), the place box, and presets that
// survive a restart. The daemon runs on the manual clock with --utc-start,
// so the Sun and the Moon are where they were then, and nothing moves
// unless the test advances time. Screenshots go to the test artifacts.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { openPage, rotordAndBrowser, screenshot, until } from './harness.mjs';

const D = Math.PI / 180;
const PHONE = { width: 390, height: 844 };
const DESKTOP = { width: 1280, height: 900 };

/** A Maidenhead locator's centre, written here from the definition. */
function locatorCentre(loc) {
  const u = loc.toUpperCase();
  let lon = (u.charCodeAt(0) - 65) * 20 - 180, lat = (u.charCodeAt(1) - 65) * 10 - 90;
  lon += Number(u[2]) * 2; lat += Number(u[3]);
  let w = 2, h = 1;
  if (u.length >= 6) {
    w = 2 / 24; h = 1 / 24;
    lon += (u.charCodeAt(4) - 65) * w; lat += (u.charCodeAt(5) - 65) * h;
  }
  return { lat: lat + h / 2, lon: lon + w / 2 };
}

/** Great-circle angle (rad) and initial bearing (deg) by the spherical law of cosines. */
function greatCircle(a, b) {
  const p1 = a.lat * D, p2 = b.lat * D, dl = (b.lon - a.lon) * D;
  const c = Math.acos(Math.sin(p1) * Math.sin(p2) + Math.cos(p1) * Math.cos(p2) * Math.cos(dl));
  const y = Math.sin(dl) * Math.cos(p2);
  const x = Math.cos(p1) * Math.sin(p2) - Math.sin(p1) * Math.cos(p2) * Math.cos(dl);
  return { c, bearing: ((Math.atan2(y, x) / D) + 360) % 360 };
}
const wrap = (v) => ((v % 360) + 360) % 360;
const angleDiff = (a, b) => Math.abs(((a - b + 540) % 360) - 180);

const run = rotordAndBrowser({ clock: 'manual', extraArgs: ['--utc-start', '2026-06-21T12:00:00Z'] });

async function station(loc) {
  const c = locatorCentre(loc);
  const r = await run.rotord.post('/api/settings', { 'station.lat_deg': c.lat, 'station.lon_deg': c.lon });
  assert.equal(r.status, 200, JSON.stringify(r.body));
  return c;
}

/** The map's Earth disc on the screen: its centre and radius in CSS pixels. */
async function disc(page) {
  const box = await page.locator('#map .map-sea').boundingBox();
  return { x: box.x + box.width / 2, y: box.y + box.height / 2, r: box.width / 2 };
}

async function openMap(size, url = '/map.html') {
  const page = await openPage(run.browser, run.rotord.url + url, size);
  await page.waitForSelector('#map[data-ready="1"]');
  return page;
}

async function azTarget() {
  const s = await run.rotord.status();
  return s.az.target_deg;
}

for (const size of [PHONE, DESKTOP]) {
  test(`the map is centred on the station for three locators at ${size.width}x${size.height}`, async () => {
    for (const loc of ['JO62QM', 'FN31PR', 'QF56']) {
      const c = await station(loc);
      const page = await openMap(size);
      const [lat, lon] = (await page.getAttribute('#map', 'data-centre')).split(' ').map(Number);
      assert.ok(Math.abs(lat - c.lat) < 1e-4 && Math.abs(lon - c.lon) < 1e-4, `${loc}: centre ${lat} ${lon}`);
      const d = await disc(page);
      const s = await page.locator('#map .map-station').boundingBox();
      assert.ok(Math.abs(s.x + s.width / 2 - d.x) < 0.5 && Math.abs(s.y + s.height / 2 - d.y) < 0.5,
        `${loc}: the station is drawn at the centre`);
      // The whole Earth fits the screen's width, with the coastlines drawn.
      assert.ok(d.x - d.r >= 0 && d.x + d.r <= size.width, `${loc}: the disc fits ${size.width} px`);
      const coast = (await page.getAttribute('#map .map-coast', 'd')) || '';
      assert.ok(coast.split('M').length > 100, `${loc}: coastlines drawn`);
      // The Sun is up somewhere, so its mark and the grey line are drawn.
      assert.equal(await page.getAttribute('#map .map-sun', 'visibility'), 'visible');
      assert.ok(((await page.getAttribute('#map .map-grey', 'd')) || '').length > 100, 'grey line');
      await screenshot(page, `map-${loc}-${size.width}.png`);
      assert.deepEqual(page.errors, []);
      await page.context().close();
    }
  });

  test(`a click on a city shows its bearing first, then turns there (${size.width} px)`, async () => {
    const home = await station('JO62QM');
    await run.rotord.post('/api/stop');
    const page = await openMap(size);
    const city = size.width < 500 ? { name: 'Tokyo', lat: 35.6762, lon: 139.6503 }
      : { name: 'New York', lat: 40.7128, lon: -74.006 };
    const g = greatCircle(home, city);
    const d = await disc(page);
    // The test's own azimuthal equidistant projection: the radius is the
    // great-circle angle (pi at the rim), the angle the bearing.
    const rho = (d.r * g.c) / Math.PI;
    const x = d.x + rho * Math.sin(g.bearing * D), y = d.y - rho * Math.cos(g.bearing * D);
    await page.mouse.click(x, y);
    await until(async () => /km/.test(await page.textContent('#pick-out')), { what: 'preview' });
    const preview = await page.textContent('#pick-out');
    const shown = Number(/: (\d+\.\d)°/.exec(preview)[1]);
    assert.ok(angleDiff(shown, g.bearing) < 0.1, `${preview} vs ${g.bearing}`);
    assert.equal(await azTarget(), null, 'nothing moves before the turn is asked for');
    await screenshot(page, `map-pick-${city.name.replace(' ', '')}-${size.width}.png`);
    await page.click('#pick-short');
    const target = await until(azTarget, { what: 'a target' });
    assert.ok(angleDiff(wrap(target), g.bearing) < 0.1,
      `${city.name}: target ${target}, bearing ${g.bearing.toFixed(3)}`);
    console.log(`${size.width} px: ${city.name} from JO62QM: bearing ${g.bearing.toFixed(3)} deg ` +
      `(this test), shown ${shown}, antenna target ${target} (off by ${angleDiff(wrap(target), g.bearing).toFixed(3)})`);
    await page.click('#pick-long');
    await until(async () => angleDiff(wrap(await azTarget()), g.bearing + 180) < 0.1,
      { what: 'the long path' });
    // The target line at once; the beam line and its wedge once the antenna has turned.
    await until(async () => (await page.getAttribute('#map .map-target', 'visibility')) === 'visible',
      { what: 'target line' });
    await run.rotord.advance(120000);
    const beamAt = async () => {
      const m = /rotate\(([-\d.e]+)\)/.exec((await page.getAttribute('#map .map-beam', 'transform')) || '');
      return m && angleDiff(wrap(Number(m[1])), g.bearing + 180) < 1.5;
    };
    await until(beamAt, { what: 'the beam line on the long path' });
    await screenshot(page, `map-turned-${size.width}.png`);
    await run.rotord.post('/api/stop');
    assert.deepEqual(page.errors, []);
    await page.context().close();
  });
}

test('the control page turns to a locator after showing its bearing', async () => {
  const home = await station('JO62QM');
  await run.rotord.post('/api/stop');
  const page = await openPage(run.browser, run.rotord.url + '/', PHONE);
  await page.fill('#place-text', 'FN31PR');
  await page.click('#place-show');
  const g = greatCircle(home, locatorCentre('FN31PR'));
  await until(async () => /km/.test(await page.textContent('#place-out')), { what: 'bearing' });
  const shown = Number(/^(\d+\.\d)°/.exec(await page.textContent('#place-out'))[1]);
  assert.ok(angleDiff(shown, g.bearing) < 0.06, `${shown} vs ${g.bearing}`);
  assert.equal(await azTarget(), null);
  await page.click('#place-form button[type="submit"]');
  const target = await until(azTarget, { what: 'a target' });
  assert.ok(angleDiff(wrap(target), g.bearing) < 0.1, `target ${target}, bearing ${g.bearing}`);
  await page.fill('#place-text', 'JO6');
  await page.click('#place-show');
  await until(async () => /4, 6, 8 or 10/.test(await page.textContent('#place-out')), { what: 'refusal' });
  await run.rotord.post('/api/stop');
  await page.context().close();
});

test('presets are one tap each and survive a restart', async () => {
  let page = await openPage(run.browser, run.rotord.url + '/', DESKTOP);
  await page.click('details summary');
  for (const [name, az, lp] of [['EU', '45', false], ['JA LP', '150', true]]) {
    await page.fill('#preset-name', name);
    await page.fill('#preset-az', az);
    await page.setChecked('#preset-long', lp);
    await page.click('#preset-form button[type="submit"]');
    await page.waitForSelector(`#presets button[data-name="${name}"]`);
  }
  // A desktop's control page has the map below the controls, no pick buttons before a pick.
  await page.waitForSelector('#map[data-ready="1"]');
  assert.equal(await page.isVisible('#pick-short'), false);
  await screenshot(page, 'control-map-1280.png');
  await page.context().close();
  await run.rotord.stop();
  await run.rotord.start();
  page = await openPage(run.browser, run.rotord.url + '/', PHONE);
  await page.waitForSelector('#presets button[data-name="JA LP"]');
  assert.equal(await page.textContent('#presets button[data-name="JA LP"]'), 'JA LP 150° LP');
  await screenshot(page, 'control-presets-390.png');
  await page.tap('#presets button[data-name="EU"]');
  await until(async () => angleDiff(wrap(await azTarget()), 45) < 0.01, { what: 'EU 45' });
  await run.rotord.post('/api/stop');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});
