// The set-up page (docs/commissioning.md) in the real browser, from an empty
// settings file to a commissioned controller with a station and a
// password: offered by the control page on the first visit, then model,
// wiring, self-commissioning (in controller time: --clock manual), station
// by locator, password. On a phone (390x844) and a desktop (1280x900);
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

before(async () => {
  dir = tempDir();
  rotord = await new Rotord({ configPath: path.join(dir, 'settings.json'), profile: 'ham4',
    clock: 'manual' }).start();
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  if (rotord) await rotord.stop();
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
