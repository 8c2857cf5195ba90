// The Track page in the real browser (Debian's chromium, playwright-core):
// TLEs pasted and refused with the reason, the next passes listed, a track
// started at the next pass, the planned pass drawn on the sky plot with the
// antenna's live position, STOP; then a client's go-tos following the ISS
// recognised on the control page's Pass line, and STOP ending it. The
// daemon runs on the manual clock with
// --utc-start, so the pass comes when the test advances to it.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import {
  cleanup, ISS, launchBrowser, openPage, ROTORD, Rotord, screenshot, tempDir, until,
} from './harness.mjs';

let browser;
let dir;
let rotord;

before(async () => {
  dir = tempDir();
  rotord = await new Rotord({
    configPath: path.join(dir, 'settings.json'),
    clock: 'manual',
    extraArgs: ['--utc-start', '2019-12-09T19:15:00Z'],
  }).start();
  const r = await rotord.post('/api/settings', { 'station.lat_deg': 39.86366, 'station.lon_deg': -119.17875 });
  assert.equal(r.status, 200);
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  if (rotord) await rotord.stop();
  cleanup(dir);
});

test('a bad TLE is refused with its reason; a good one is listed with its passes', async () => {
  const page = await openPage(browser, rotord.url + '/track.html');
  await page.fill('#tle-text', ISS.replace('9991', '9990'));
  await page.click('#tle-store');
  await until(async () => /checksum/.test(await page.textContent('#tle-msg')), { what: 'refusal' });
  await page.fill('#tle-text', ISS);
  await page.click('#tle-store');
  await until(async () => /stored: 1 new/.test(await page.textContent('#tle-msg')), { what: 'stored' });
  await until(async () => /ISS \(ZARYA\)/.test(await page.textContent('#objects')), { what: 'listed' });
  assert.equal(await page.inputValue('#object'), '25544');
  await until(async () => /12-09 19:26:15/.test(await page.textContent('#passes')), { what: 'passes' });
  assert.match(await page.textContent('#passes'), /87\.8°/);
  // The refused paste's 422 is the browser's only complaint.
  assert.deepEqual(page.errors.filter((e) => !/status of 422/.test(e)), []);
  await page.context().close();
});

test('tracking at the next pass draws the plan and follows it; STOP ends it', async () => {
  const page = await openPage(browser, rotord.url + '/track.html');
  await until(async () => (await page.inputValue('#object')) === '25544', { what: 'object list' });
  await page.click('#track-next');
  await until(async () => /tracking ISS/.test(await page.textContent('#msg')), { what: 'started' });
  await rotord.untilAdvancing(async () => /waiting|prepositioning/.test(await page.textContent('#phase')),
    { stepMs: 1000, what: 'planned' });
  assert.match(await page.textContent('#pass-times'), /19:26:15 \/ 19:37:04/);
  assert.match(await page.textContent('#plan'), /flipped|not flipped/);
  const points = await page.getAttribute('#pass-path', 'points');
  assert.ok(points.split(' ').length > 50, points);
  // To the middle of the pass (19:30): the antenna is on the plot, near the target.
  await rotord.advance(15 * 60 * 1000);
  await until(async () => /^tracking/.test(await page.textContent('#phase')), { what: 'tracking' });
  await until(async () => (await page.getAttribute('#antenna', 'visibility')) === 'visible', { what: 'antenna' });
  assert.equal(await page.getAttribute('#sky-target', 'visibility'), 'visible');
  const at = async (id) => [Number(await page.getAttribute(id, 'cx')), Number(await page.getAttribute(id, 'cy'))];
  await until(async () => {
    const [ax, ay] = await at('#antenna');
    const [tx, ty] = await at('#sky-target');
    return Math.hypot(ax - tx, ay - ty) < 10;  // within 10 deg of elevation on the plot
  }, { what: 'antenna near the target' });
  await screenshot(page, 'track.png');
  await page.click('#stop');
  await until(async () => /^off/.test(await page.textContent('#phase')), { what: 'stopped' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('a client\'s go-tos following the ISS are recognised on the control page; STOP ends it', async () => {
  // The rest of the pass (the track above was stopped near culmination): a
  // client (REST from this address) sends the ISS's position as rotord
  // predict gives it, one go-to every 2 s of controller time.
  const tle = `${dir}/iss.tle`;
  writeFileSync(tle, ISS + '\n');
  const page = await openPage(browser, rotord.url + '/');
  const start = Date.parse('2019-12-09T19:15:00Z');
  for (let n = 0; n < 4; n++) {
    const ms = (await rotord.status()).time_ms;
    if (ms % 1000 !== 0) await rotord.advance(1000 - (ms % 1000));
    const t = new Date(start + (await rotord.status()).time_ms).toISOString().replace(/\.\d+Z$/, 'Z');
    const p = spawnSync(ROTORD, ['predict', '--tle', tle, '--lat', '39.86366', '--lon', '-119.17875',
      '--alt', '0', '--from', t, '--to', t, '--step', '1'], { encoding: 'utf8' });
    const [, az, el] = p.stdout.trim().split('\n')[1].split(',').map(Number);
    assert.ok(el > 0, p.stdout);
    assert.equal((await rotord.post('/api/goto', { az, el })).status, 200);
    await rotord.advance(2000);
  }
  await until(async () => /following ISS \(ZARYA\)/.test(await page.textContent('#recognised')),
    { what: 'recognised' });
  assert.equal(await page.isVisible('#recognised-row'), true);
  await page.click('#stop');
  await until(async () => /recognition ended \(stop\)/.test(await page.textContent('#recognised')),
    { what: 'ended' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});
