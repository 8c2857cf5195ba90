// The calibration cards of the settings page in Debian's chromium
// (playwright-core): a pot rotator (`rotord --sim g5500`) for the volts, the
// offset-consistent two-point calibration and the multi-point table, and an
// MA3 rotator (`rotord --sim spid`, its encoder mounted 20 deg short of
// north) for the encoder zero and direction. An absolute sensor's zero is
// the controller's known-bearing step: the card shows its proposal beside
// the value in force and writes it only on Accept.
import assert from 'node:assert/strict';
import { mkdirSync } from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import {
  ARTIFACTS, cleanup, launchBrowser, openPage, request, Rotord, tempDir, until,
} from './harness.mjs';

let browser;
let dir;
let pot;  // g5500: potentiometers
let ma3;  // spid: MA3 encoders

before(async () => {
  dir = tempDir();
  [pot, ma3, browser] = await Promise.all([
    new Rotord({ configPath: path.join(dir, 'pot.json') }).start(),
    new Rotord({ configPath: path.join(dir, 'ma3.json'), profile: 'spid',
      extraArgs: ['--sim-sensor-mount', '-20'] }).start(),
    launchBrowser(),
  ]);
});

after(async () => {
  if (browser) await browser.close();
  await Promise.all([pot && pot.stop(), ma3 && ma3.stop()]);
  cleanup(dir);
});

const settingsOf = async (r) => (await request(r.url + '/api/settings')).body;
const commissioning = async (r) => (await request(r.url + '/api/commission')).body;

/**
 * Clicks `button` (the card's bearing button) and waits for `done` in the
 * message: the controller's known bearing (GET /api/commission) proposed the
 * setting, and the card accepted that value, not one of its own.
 */
async function viaKnownBearing(page, r, button, done) {
  await page.click(button);
  await until(async () => (await page.textContent('#msg')).includes(done), { what: done });
  const c = await commissioning(r);
  assert.equal(c.state, 'done');
  assert.equal(c.proposal.length, 1);
  const [p] = c.proposal;
  assert.equal((await settingsOf(r))[p.key], p.value, `${p.key} as the controller proposed it`);
  return p;
}

// Chromium logs each refused POST (422) as a failed resource: those are expected.
const unexpected = (errors) => errors.filter((e) => !/status of 422/.test(e));

async function openSettings(r, options) {
  const page = await openPage(browser, r.url + '/settings.html', options);
  await page.waitForSelector('#cal-az');
  await page.waitForSelector('#conn.live');
  return page;
}

async function shoot(page, name) {
  mkdirSync(ARTIFACTS, { recursive: true });
  await page.locator('#calibration').screenshot({ path: path.join(ARTIFACTS, name) });
}

/**
 * Waits until the rotator stands still, every latched fault is absent and the
 * reading has stopped changing: a settings change is applied at the next
 * tick, and a filtered sensor may still be settling on a motionless antenna.
 */
async function settled(r, axis = 'az') {
  let last = null;
  let previous = null;
  try {
    return await until(async () => {
      last = await r.status();
      const still = !last.moving && last[axis].fault === 'none';
      const steady = still && previous !== null &&
        Math.abs(last[axis].position_deg - previous[axis].position_deg) < 0.3;
      previous = still ? last : null;
      return steady && last;
    }, { timeout: 20000, interval: 250, what: 'standstill without fault' });
  } catch (e) {
    throw new Error(`${e.message}; ${axis}: ${JSON.stringify(last && last[axis])}`);
  }
}

test('pot: raw counts are shown in volts too (12-bit ADC, 3.3 V)', async () => {
  const page = await openSettings(pot);
  await until(async () => /V$/.test(await page.textContent('#cal-az-volts')), { what: 'volts' });
  const counts = parseFloat(await page.textContent('#cal-az-raw'));
  const volts = parseFloat(await page.textContent('#cal-az-volts'));
  assert.ok(Math.abs(volts - (counts * 3.3) / 4095) < 0.002, `${counts} counts shown as ${volts} V`);
  const s = await pot.status();
  assert.equal(s.az.sensor, 'pot');
  assert.equal(s.az.raw_full_scale, 4095);
  assert.ok(Math.abs(s.az.raw_volts - (s.az.raw * 3.3) / 4095) < 1e-4);
  // Each table row shows its point in volts as well.
  const row = page.locator('#cal-az-points tr[data-role="hi"] td');
  const hiCounts = (await settingsOf(pot))['az.pot_cal_hi_counts'];
  assert.ok(Math.abs(parseFloat(await row.nth(2).textContent()) - (hiCounts * 3.3) / 4095) < 0.002);
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('pot: "antenna now at X" with an offset makes the display read X', async () => {
  assert.equal((await pot.post('/api/settings', { 'az.offset_deg': 10 })).status, 200);
  const page = await openSettings(pot);
  await until(async () => (await page.locator('#cal-az .note').textContent()).includes('offset_deg (10°)'),
    { what: 'the offset note' });
  await page.fill('#cal-az-deg', '200');
  await page.click('#cal-az-lo');
  await until(async () => (await page.textContent('#msg')).includes('low point set'), { what: 'cal set' });
  const v = await settingsOf(pot);
  assert.equal(v['az.pot_cal_lo_deg'], 190, 'stored without the offset, as GS-232 O does');
  const s = await settled(pot);
  assert.ok(Math.abs(s.az.position_deg - 200) < 0.5, `reads ${s.az.position_deg}`);
  await until(async () => Math.abs(parseFloat(await page.textContent('#cal-az-angle')) - 200) < 0.5,
    { what: 'the page shows 200' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('pot: multi-point table, add and remove; a refused table saves nothing', async () => {
  // From the previous test: low point (raw at 200) = 190 + offset 10.
  assert.equal((await pot.post('/api/goto', { az: 300 })).status, 200);
  await until(async () => {
    const s = await pot.status();
    return !s.moving && Math.abs(s.az.position_deg - 300) <= 1.5;
  }, { timeout: 30000, what: 'arrival at 300' });
  const page = await openSettings(pot, { width: 1280, height: 1000 });
  assert.equal(await page.locator('#cal-az-points tbody tr').count(), 2);
  assert.equal(await page.locator('#cal-az-points .remove:enabled').count(), 0, 'two points stay');

  // A non-linear pot: here the antenna really points at 305.
  await page.fill('#cal-az-deg', '305');
  await page.click('#cal-az-add');
  await until(async () => (await page.textContent('#msg')).includes('point added'), { what: 'point added' });
  let v = await settingsOf(pot);
  assert.equal(v['az.pot_cal_mid_points'], 1);
  assert.equal(v['az.pot_cal_m1_deg'], 295);
  assert.ok(v['az.pot_cal_lo_counts'] < v['az.pot_cal_m1_counts'] &&
    v['az.pot_cal_m1_counts'] < v['az.pot_cal_hi_counts'], 'kept in counts order');
  await until(async () => (await page.locator('#cal-az-points tbody tr').count()) === 3, { what: '3 rows' });
  const rows = await page.locator('#cal-az-points tbody tr').evaluateAll(
    (trs) => trs.map((tr) => parseFloat(tr.children[1].textContent)));
  assert.deepEqual(rows, [...rows].sort((a, b) => a - b), 'rows sorted by counts');
  const s = await settled(pot);
  assert.ok(Math.abs(s.az.position_deg - 305) < 0.5, `reads ${s.az.position_deg}`);
  await shoot(page, 'calibration-pot-1280.png');

  // The same position at 150: counts and angles no longer rise together.
  await page.fill('#cal-az-deg', '150');
  await page.click('#cal-az-add');
  await until(async () => (await page.textContent('#cal-az-error')).includes('rise or fall together'),
    { what: 'the refusal next to the table' });
  assert.deepEqual(await settingsOf(pot), v, 'nothing saved');
  assert.equal(await page.locator('#cal-az-points tbody tr').count(), 3);

  await page.click('#cal-az-points .remove[data-role="m1"]');
  await until(async () => (await settingsOf(pot))['az.pot_cal_mid_points'] === 0, { what: 'point removed' });
  await until(async () => (await page.locator('#cal-az-points tbody tr').count()) === 2, { what: '2 rows' });
  assert.equal(await page.textContent('#cal-az-error'), '');
  v = await settingsOf(pot);
  assert.equal(v['az.pot_cal_lo_deg'], 190, 'the end points are untouched');
  assert.deepEqual(unexpected(page.errors), []);
  await page.context().close();

  const phone = await openSettings(pot, { width: 360, height: 780, colorScheme: 'dark' });
  const overflow = await phone.evaluate(() => document.documentElement.scrollWidth > innerWidth);
  assert.equal(overflow, false, 'no horizontal scroll at 360 px');
  await shoot(phone, 'calibration-pot-360-dark.png');
  assert.deepEqual(phone.errors, []);
  await phone.context().close();
});

test('magnetometer: raw field, spin calibration over a full turn fixes the heading', async () => {
  // Every simulated azimuth has a QMC5883L on a steel mast (sim/sensors.hpp):
  // the default calibration (+-1000) reads a distorted heading.
  // The pot tests above miscalibrated the pot on purpose; it is the reference here.
  assert.equal((await pot.post('/api/settings/reset')).status, 200);
  assert.equal((await pot.post('/api/settings', { 'az.sensor': 'mag' })).status, 200);
  const limit = async (dir) => {
    assert.equal((await pot.post('/api/move', { dir, hold_ms: 0 })).status, 200);
    await until(async () => {
      const s = await pot.status();
      return !s.moving && s.az[dir === 'cw' ? 'limit_cw' : 'limit_ccw'];
    }, { timeout: 30000, what: `the ${dir} limit` });
  };
  await limit('ccw');
  const page = await openSettings(pot);
  await until(async () => /^x -?\d+, y -?\d+, z \d+$/.test(await page.textContent('#cal-az-mag')),
    { what: 'raw field' });
  assert.match(await page.textContent('#cal-az-spin-range'), /Saved: x -1000/);
  await page.click('#cal-az-spin');
  assert.match(await page.textContent('#cal-az-spin-range'), /^Recording/);
  await limit('cw');  // 450 deg of travel: more than a full circle
  await until(async () => !(await page.isDisabled('#cal-az-spin-save')), { what: 'a full range' });
  await page.click('#cal-az-spin-save');
  await until(async () => (await page.textContent('#msg')).includes('magnetometer calibration saved'),
    { what: 'saved' });
  const v = await settingsOf(pot);
  // The simulated field: x = 300 +- 1200, y = -150 +- 900 (plus 2 counts of noise).
  for (const [key, want] of [['mag.x_min', -900], ['mag.x_max', 1500], ['mag.y_min', -1050],
    ['mag.y_max', 750]]) {
    assert.ok(Math.abs(v[key] - want) <= 25, `${key} = ${v[key]}, field says ${want}`);
  }
  const heading = (await settled(pot)).az.position_deg;
  // The card shows what was saved (the recorded minimum may fall a few counts
  // short of -900 when a loaded machine delivers fewer updates).
  await until(async () => (await page.textContent('#cal-az-spin-range'))
    .startsWith(`Saved: x ${v['mag.x_min']} … ${v['mag.x_max']}`),
  { what: 'the saved extremes on the card' });
  await shoot(page, 'calibration-mag-1280.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();
  // The pot on the same shaft agrees with the calibrated heading.
  assert.equal((await pot.post('/api/settings', { 'az.sensor': 'pot' })).status, 200);
  // The next tick applies the switch: from then on there is no raw field.
  await until(async () => (await pot.status()).az.mag === null, { what: 'the pot in charge' });
  const truth = (await settled(pot)).az.position_deg;
  const diff = Math.abs((((heading - truth) % 360) + 540) % 360 - 180);
  assert.ok(diff < 1.5, `magnetometer ${heading} vs pot ${truth}`);
});

test('magnetometer: "set this heading as N" turns the declination', async () => {
  // The spin calibration of the previous test is saved; the pot is in charge.
  // At 200 deg the single-turn heading can only mean 200 (not 560 or -160).
  assert.equal((await pot.post('/api/goto', { az: 200 })).status, 200);
  await until(async () => {
    const s = await pot.status();
    return !s.moving && Math.abs(s.az.position_deg - 200) <= 1.5;
  }, { timeout: 30000, what: 'the rotator at 200' });
  assert.equal((await pot.post('/api/settings', { 'az.sensor': 'mag' })).status, 200);
  await until(async () => (await pot.status()).az.mag !== null, { what: 'the magnetometer in charge' });
  const page = await openSettings(pot);
  const s0 = await settled(pot);
  const declination0 = (await settingsOf(pot))['mag.declination_deg'];
  const n = Math.round(s0.az.position_deg) + 7;
  await page.fill('#cal-az-deg', String(n));
  assert.equal(await page.textContent('#cal-az-align'), `Set this heading as ${n}°`);
  const p = await viaKnownBearing(page, pot, '#cal-az-align', `this heading is now ${n}°`);
  assert.equal(p.key, 'mag.declination_deg');
  const s = await settled(pot);
  assert.ok(Math.abs(s.az.position_deg - n) < 0.5, `reads ${s.az.position_deg}, wanted ${n}`);
  assert.equal(s.az.fault, 'none');
  const declination = (await settingsOf(pot))['mag.declination_deg'];
  // The controller turns by what its reading lacked; the sensor's noise
  // moves that reading by a few hundredths between two updates.
  assert.ok(Math.abs(declination - declination0 - (n - s0.az.position_deg)) < 0.5,
    `declination ${declination0} -> ${declination}`);
  await until(async () => (await page.textContent('#cal-az-align-now'))
    .startsWith(`mag.declination_deg = ${declination.toFixed(2)}`), { what: 'the new declination on the card' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('MA3: code and duty, "set this position as N" through the known bearing, direction keeps the angle', async () => {
  assert.equal((await ma3.post('/api/settings', { 'az.offset_deg': 5 })).status, 200);
  const page = await openSettings(ma3);
  await until(async () => / of 4096$/.test(await page.textContent('#cal-az-raw')), { what: 'code' });
  assert.match(await page.textContent('#cal-az-duty'), /%$/);
  const s0 = await settled(ma3);
  assert.equal(s0.az.sensor, 'ma3');
  assert.equal(s0.az.raw_volts, null);
  // The antenna stands at 180 (where the simulator starts it); the encoder,
  // mounted 20 deg short, reads 160, and the offset adds 5.
  assert.ok(Math.abs(s0.az.position_deg - 165) < 0.5, `reads ${s0.az.position_deg}`);
  const n = 185;  // the true bearing and the offset

  await page.fill('#cal-az-deg', String(n));
  assert.equal(await page.textContent('#cal-az-zero'), `Set this position as ${n}°`);
  assert.equal((await settingsOf(ma3))['az.ma3_zero_deg'], 0);
  const p = await viaKnownBearing(page, ma3, '#cal-az-zero', `this position is now ${n}°`);
  assert.equal(p.key, 'az.ma3_zero_deg');
  // The MA3 reads its code less the zero: 160 - 340 = 180 (mod 360).
  assert.ok(Math.abs(p.value - 340) < 0.5, `proposed ${p.value}`);
  let s = await settled(ma3);
  assert.ok(Math.abs(s.az.position_deg - n) < 0.3, `reads ${s.az.position_deg}, wanted ${n}`);
  await until(async () => Math.abs(parseFloat(await page.textContent('#cal-az-angle')) - n) < 0.3,
    { what: `the page shows ${n}` });
  console.log(`MA3 read ${s0.az.position_deg.toFixed(2)} at ${n}: zero ${p.value} proposed and ` +
    `accepted, reads ${s.az.position_deg.toFixed(2)}`);

  // The direction: the controller turns the zero so that the reading stays
  // (the known bearing again, right after the direction was saved).
  await page.check('#cal-az-reverse');
  await until(async () => (await page.textContent('#msg')).includes('reversed, still'), { what: 'reversed' });
  let v = await settingsOf(ma3);
  assert.equal(v['az.ma3_reverse'], true);
  assert.equal((await commissioning(ma3)).proposal[0].value, v['az.ma3_zero_deg']);
  s = await settled(ma3);
  assert.ok(Math.abs(s.az.position_deg - n) < 0.3, `reversing moved the angle to ${s.az.position_deg}`);
  await page.uncheck('#cal-az-reverse');
  await until(async () => (await page.textContent('#msg')).includes('normal, still'), { what: 'normal' });
  v = await settingsOf(ma3);
  assert.equal(v['az.ma3_reverse'], false);
  assert.ok(Math.abs(v['az.ma3_zero_deg'] - p.value) < 0.3, `zero ${v['az.ma3_zero_deg']}`);
  s = await settled(ma3);
  assert.ok(Math.abs(s.az.position_deg - n) < 0.3);
  await shoot(page, 'calibration-ma3-1280.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();

  const phone = await openSettings(ma3, { width: 360, height: 780 });
  await phone.waitForSelector('#cal-el-zero');
  await shoot(phone, 'calibration-ma3-360.png');
  assert.deepEqual(phone.errors, []);
  await phone.context().close();
});
