// The set-up page (docs/commissioning.md) in the real browser, from an empty
// settings file to a commissioned controller with a station and a
// password: offered by the control page on the first visit, then model,
// wiring, self-commissioning (in controller time: --clock manual), station
// by locator, password. On a phone (390x844, a Ham IV) and a desktop
// (1280x900, a G-5500 walked to a Sun track on the commissioned settings);
// screenshots in test-artifacts/.
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, test } from 'node:test';

import {
  cleanup, launchBrowser, openPage, request, Rotord, screenshot, tempDir, until,
} from './harness.mjs';

let browser;
let dir;
let rotord;
let desk;  // the desktop walk's own daemon, from its own empty settings file

before(async () => {
  dir = tempDir();
  rotord = await new Rotord({ configPath: path.join(dir, 'settings.json'), profile: 'ham4',
    clock: 'manual' }).start();
  // Mid-morning in Munich on midsummer's day: the Sun is up, at about
  // az 125, el 55, when the walk ends.
  desk = await new Rotord({ configPath: path.join(dir, 'desk.json'), profile: 'g5500',
    clock: 'manual', extraArgs: ['--utc-start', '2019-06-21T08:30:00Z'] }).start();
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  if (rotord) await rotord.stop();
  if (desk) await desk.stop();
  cleanup(dir);
});

test('from an empty settings file to a commissioned, located, protected controller', async () => {
  const phone = await openPage(browser, rotord.url + '/', { width: 390, height: 844 });
  await phone.waitForSelector('#setup-offer:not([hidden])');
  await phone.click('#setup-offer a');
  await phone.waitForURL(/setup\.html$/);
  await phone.waitForSelector('#model option[value="hygain-ham4"]', { state: 'attached' });

  // 1. The model: its figures with their sources, then saved.
  await phone.selectOption('#model', 'hygain-ham4');
  assert.match(await phone.textContent('#figures'), /\[HG3\] 360 deg/);
  assert.match(await phone.textContent('#figures'), /not published: measured/);
  await phone.click('#use-model');
  await until(async () => /Saved/.test(await phone.textContent('#model-msg')), { what: 'model saved' });
  // A reload keeps the owner's model (it showed the first of the list, the
  // G-5500, before).
  await phone.reload();
  await phone.waitForSelector('#model option[value="hygain-ham4"]', { state: 'attached' });
  await until(async () => /\[HG3\] 360 deg/.test(await phone.textContent('#figures')), { what: 'figures' });
  assert.equal(await phone.inputValue('#model'), 'hygain-ham4');

  // 2. The wiring: the simulator has none of its own, so the page asks
  // which board's to prepare. A relay drive with a brake and a pot: the
  // relay boards the docs describe, no PWM pins, no elevation, and only
  // the chosen platform's pins.
  await phone.waitForSelector('#wiring-for-row:not([hidden])');
  const keys = () => phone.$$eval('#pins input', (l) => l.map((i) => i.dataset.key));
  const boards = () => phone.$$eval('#boards button', (l) => l.map((b) => b.id));
  await phone.selectOption('#wiring-for', 'pico_w');
  let pins = await keys();
  assert.ok(pins.includes('pins.az_cw') && pins.includes('pins.az_brake') && pins.includes('pins.az_pot'),
    pins.join());
  assert.ok(!pins.some((k) => k.includes('pwm') || k.startsWith('gpiod.') || k.startsWith('pins.el_')),
    pins.join());
  assert.deepEqual(await boards(), ['board-pico-relay']);
  await phone.fill('#pin-pins\\.az_cw', '2.5');
  await phone.click('#save-pins');
  assert.match(await phone.textContent('#pins-msg'), /pins\.az_cw: a whole number/);
  // The Pico W's relay board: the documented wiring (docs/hardware.md).
  await phone.click('#board-pico-relay');
  assert.equal(await phone.inputValue('#pin-pins\\.az_cw'), '5');
  assert.equal(await phone.inputValue('#pin-pins\\.az_brake'), '8');
  // The Raspberry Pi: its lines and its two relay boards.
  await phone.selectOption('#wiring-for', 'gpiod');
  pins = await keys();
  assert.ok(pins.includes('gpiod.az_cw') && pins.includes('gpiod.az_brake') && pins.includes('iio.az_device'),
    pins.join());
  assert.ok(!pins.some((k) => k.startsWith('pins.') || k.startsWith('pwm.')), pins.join());
  assert.deepEqual(await boards(), ['board-pi-relay-high', 'board-pi-relay-low']);
  await phone.click('#board-pi-relay-low');
  assert.equal(await phone.isChecked('#pin-gpiod\\.outputs_active_low'), true);
  await phone.fill('#pin-gpiod\\.az_l1', '13');
  await phone.click('#save-pins');
  await until(async () => /Saved/.test(await phone.textContent('#pins-msg')), { what: 'wiring saved' });
  const wired = (await request(rotord.url + '/api/settings')).body;
  assert.equal(wired['gpiod.outputs_active_low'], true);
  assert.equal(wired['gpiod.az_l1'], 13);
  assert.equal(wired['gpiod.az_cw'], 17);

  // 3. Self-commissioning: the simulated Ham IV's switches sit 1 deg
  // outside 0..360. Controller time runs while the page follows the run.
  // Its pot has no zero to set: no known-bearing step.
  assert.equal(await phone.$eval('#step-bearing', (o) => o.disabled), true);
  await phone.fill('#ccw', '-1');
  await phone.fill('#cw', '361');
  await phone.click('#start');
  await until(async () => /running/.test(await phone.textContent('#run-state')), { what: 'running' });
  assert.ok(await phone.isVisible('#stop'));
  await rotord.untilAdvancing(async () =>
    (await request(rotord.url + '/api/commission')).body.state === 'done',
  { stepMs: 5000, timeout: 60000, what: 'commissioning done' });
  await until(async () => !(await phone.isDisabled('#accept')), { what: 'accept enabled' });
  assert.match(await phone.textContent('#proposal'), /az\.pot_cal_lo_counts/);
  const points = await phone.getAttribute('#pos-line', 'points');
  assert.ok(points.split(' ').length > 50, points);
  await phone.click('#accept');
  await until(async () => /Saved/.test(await phone.textContent('#accept-msg')), { what: 'accepted' });
  const settings = (await request(rotord.url + '/api/settings')).body;
  assert.equal(settings['az.pot_cal_lo_deg'], -1);
  assert.equal(settings['az.has_brake'], true);

  // 4. The station from a Maidenhead locator, and the clock in words (the
  // host's NTP state: this machine's, whichever it is).
  assert.match(await phone.textContent('#clock'),
    /^The (system clock is (synchronized by NTP|not synchronized)|kernel does not say)/);
  await phone.fill('#locator', 'JN58td');
  assert.equal(await phone.inputValue('#lat'), '48.1458');
  assert.equal(await phone.inputValue('#lon'), '11.6250');
  await phone.click('#save-station');
  await until(async () => /Saved/.test(await phone.textContent('#station-msg')), { what: 'station saved' });
  assert.equal((await request(rotord.url + '/api/settings')).body['station.lat_deg'], 48.1458);
  assert.equal((await request(rotord.url + '/api/setup')).body.configured, true);
  await screenshot(phone, 'setup-390x844.png');

  const desk = await openPage(browser, rotord.url + '/setup.html', { width: 1280, height: 900 });
  await until(async () => /done/.test(await desk.textContent('#run-state')), { what: 'desktop state' });
  // Another browser, nothing chosen in it: the model the settings in force
  // match (after commissioning moved the limits), not the first of the list.
  assert.equal(await desk.inputValue('#model'), 'hygain-ham4');
  const width = await desk.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(width <= 1280, `no sideways scrolling: ${width}`);
  await screenshot(desk, 'setup-1280x900.png');
  assert.deepEqual(desk.errors, []);
  await desk.context().close();
  const phoneWidth = await phone.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(phoneWidth <= 390, `no sideways scrolling on the phone: ${phoneWidth}`);

  // 5. Access: a password; the API then wants a login.
  await phone.fill('#password', 'short');
  await phone.click('#save-password');
  await until(async () => /at least 8/.test(await phone.textContent('#password-msg')), { what: 'refused' });
  await phone.fill('#password', 'rotator-on-the-roof');
  await phone.click('#save-password');
  await until(async () => (await request(rotord.url + '/api/status')).status === 401,
    { timeout: 60000, what: 'access control on' });
  // The short password's 422 is the one resource error the browser logs.
  assert.deepEqual(phone.errors.filter((e) => !/status of 422/.test(e)), []);
  await phone.context().close();
});

test('on a desktop, from an empty settings file to tracking the Sun on the commissioned settings',
  async () => {
    const get = async (p) => (await request(desk.url + p)).body;
    const page = await openPage(browser, desk.url + '/', { width: 1280, height: 900 });
    await page.waitForSelector('#setup-offer:not([hidden])');
    await page.click('#setup-offer a');
    await page.waitForURL(/setup\.html$/);
    await page.waitForSelector('#model option[value="yaesu-g5500"]', { state: 'attached' });
    await page.selectOption('#model', 'yaesu-g5500');
    await page.click('#use-model');
    await until(async () => /Saved/.test(await page.textContent('#model-msg')), { what: 'model saved' });

    // A Raspberry Pi with the relay board energised by a high input.
    await page.waitForSelector('#wiring-for-row:not([hidden])');
    await page.selectOption('#wiring-for', 'gpiod');
    await page.click('#board-pi-relay-high');
    await page.click('#save-pins');
    await until(async () => /Saved/.test(await page.textContent('#pins-msg')), { what: 'wiring saved' });
    assert.equal((await get('/api/settings'))['gpiod.az_cw'], 17);

    // The simulated G-5500's azimuth switches sit 1 deg outside 0..450.
    await page.fill('#ccw', '-1');
    await page.fill('#cw', '451');
    await page.click('#start');
    await until(async () => /running/.test(await page.textContent('#run-state')), { what: 'running' });
    await desk.untilAdvancing(async () => (await get('/api/commission')).state === 'done',
      { stepMs: 5000, timeout: 60000, what: 'commissioning done' });
    await until(async () => !(await page.isDisabled('#accept')), { what: 'accept enabled' });
    await page.click('#accept');
    await until(async () => /Saved/.test(await page.textContent('#accept-msg')), { what: 'accepted' });
    const accepted = await get('/api/settings');
    assert.equal(accepted['az.pot_cal_lo_deg'], -1);
    assert.equal(accepted['az.pot_cal_hi_deg'], 451);

    await page.fill('#locator', 'JN58td');
    await page.click('#save-station');
    await until(async () => /Saved/.test(await page.textContent('#station-msg')), { what: 'station saved' });
    const width = await page.evaluate(() => document.documentElement.scrollWidth);
    assert.ok(width <= 1280, `no sideways scrolling: ${width}`);
    await screenshot(page, 'setup-walk-1280x900.png');

    // Tracking-ready: the Sun, tracked on the settings commissioning
    // proposed, is reached within the accepted tolerance.
    const r = await desk.post('/api/track', { body: 'sun', when: 'now' });
    assert.equal(r.status, 200, JSON.stringify(r.body));
    const track = await desk.untilAdvancing(async () => {
      const t = await get('/api/track');
      const s = await get('/api/status');
      return t.phase === 'tracking' && Math.abs(s.az.position_deg - t.antenna_target.az) <= accepted['az.tolerance_deg'] &&
        Math.abs(s.el.position_deg - t.antenna_target.el) <= 1.5 ? { t, s } : null;
    }, { stepMs: 2000, timeout: 60000, what: 'on the Sun' });
    console.log(`desktop walk: Sun at az ${track.t.sky.az.toFixed(1)} el ${track.t.sky.el.toFixed(1)}; ` +
      `antenna az ${track.s.az.position_deg.toFixed(2)} el ${track.s.el.position_deg.toFixed(2)}, ` +
      `tolerance ${accepted['az.tolerance_deg']} deg (commissioned)`);
    assert.ok(track.t.sky.el > 40 && track.t.sky.az > 90 && track.t.sky.az < 160, JSON.stringify(track.t.sky));
    assert.deepEqual(page.errors, []);
    await page.context().close();
  });

test('an absolute sensor\'s zero from a known bearing, on a phone', async () => {
  // The SPID's azimuth MA3 coupled 20 deg short of north: the antenna at
  // 180 (where the simulator starts it) reads 160.
  const spid = await new Rotord({ configPath: path.join(dir, 'spid.json'), profile: 'spid',
    clock: 'manual', extraArgs: ['--sim-sensor-mount', '-20'] }).start();
  try {
    await spid.advance(1000);
    const az = async () => (await spid.status()).az.position_deg;
    const off = (deg, bearing) => Math.abs(((deg - bearing + 540) % 360) - 180);
    assert.ok(off(await az(), 160) < 0.2, String(await az()));
    const page = await openPage(browser, spid.url + '/setup.html', { width: 390, height: 844 });
    await page.waitForSelector('#model option[value="spid-ras"]', { state: 'attached' });
    await page.selectOption('#axis', 'az');
    await page.selectOption('#step', 'bearing');
    assert.ok(await page.isVisible('#bearing') && !(await page.isVisible('#ccw')));
    // Out of range, then nothing: refused with the controller's reason.
    await page.fill('#bearing', '400');
    await page.click('#start');
    await until(async () => /0 to 360/.test(await page.textContent('#run-state')), { what: 'refused' });
    await page.fill('#bearing', '');
    await page.evaluate(() => { document.getElementById('run-state').textContent = ''; });
    await page.click('#start');
    await until(async () => /0 to 360/.test(await page.textContent('#run-state')), { what: 'refused empty' });
    assert.equal((await request(spid.url + '/api/settings')).body['az.ma3_zero_deg'], 0);

    await page.fill('#bearing', '180');
    await page.click('#start');
    await until(async () => /az\.ma3_zero_deg/.test(await page.textContent('#proposal')), { what: 'proposal' });
    const row = await page.$$eval('#proposal tbody tr', (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
    assert.equal(row.length, 1, JSON.stringify(row));
    assert.equal(row[0][0], 'az.ma3_zero_deg');
    assert.ok(Math.abs(Number(row[0][1]) - 340) < 0.2, row[0][1]);  // 160 - 340 = 180 (mod 360)
    assert.equal(row[0][2], '0');
    await screenshot(page, 'setup-bearing-390x844.png');
    await page.click('#accept');
    await until(async () => /Saved/.test(await page.textContent('#accept-msg')), { what: 'accepted' });
    const after = await spid.untilAdvancing(async () => {
      const deg = await az();
      return off(deg, 180) < 0.2 ? deg : null;
    }, { stepMs: 500, timeout: 20000, what: 'reads the bearing' });
    console.log(`known bearing: MA3 read 160 at bearing 180; az.ma3_zero_deg ${row[0][1]} accepted; reads ${after.toFixed(2)}`);
    const phoneWidth = await page.evaluate(() => document.documentElement.scrollWidth);
    assert.ok(phoneWidth <= 390, `no sideways scrolling on the phone: ${phoneWidth}`);
    // The two refusals' 422s are the resource errors the browser logs.
    assert.deepEqual(page.errors.filter((e) => !/status of 422/.test(e)), []);
    await page.context().close();
  } finally {
    await spid.stop();
  }
});
