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

  // 2. The wiring: a relay drive with a brake and a pot: no PWM pins.
  const pins = await phone.$$eval('#pins input', (l) => l.map((i) => i.dataset.key));
  assert.ok(pins.includes('pins.az_cw') && pins.includes('gpiod.az_brake'), pins.join());
  assert.ok(!pins.some((k) => k.includes('pwm')), pins.join());
  assert.ok(!pins.some((k) => k.startsWith('pins.el_')), pins.join());
  await phone.fill('#pin-pins\\.az_cw', '2.5');
  await phone.click('#save-pins');
  assert.match(await phone.textContent('#pins-msg'), /pins\.az_cw: a whole number/);
  await phone.fill('#pin-pins\\.az_cw', '5');

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

  // 4. The station from a Maidenhead locator.
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
