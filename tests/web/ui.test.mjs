// The real web page in Debian's chromium (playwright-core) against a running
// `rotord --sim g5500 --clock manual`: controller time moves only when a test
// advances it; the network's timeouts (the hold-to-move dead-man) stay on the
// wall clock.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import {
  openPage, request, rotordAndBrowser, screenshot, until,
} from './harness.mjs';

const run = rotordAndBrowser({ clock: 'manual' });

const displayedAz = async (page) => parseFloat(await page.textContent('#az'));

/** The control page is live: its event stream has delivered a position. */
async function openLive(url) {
  const page = await openPage(run.browser, url);
  await page.waitForSelector('#conn.live');
  await until(async () => (await page.textContent('#az')).includes('°'), { what: 'first live position' });
  return page;
}

test('control page loads without console errors, phone and desktop, light and dark', async () => {
  for (const [width, height, scheme] of [[360, 780, 'light'], [360, 780, 'dark'],
    [1280, 900, 'light'], [1280, 900, 'dark']]) {
    const page = await openPage(run.browser, run.rotord.url + '/', { width, height, colorScheme: scheme });
    await page.waitForSelector('#conn.live');
    await until(async () => (await page.textContent('#az')).includes('°'), { what: 'azimuth' });
    // What the axis has been through (docs/care.md): no slip, no rejected reading.
    assert.equal(await page.textContent('#care'), 'az 0 slips, 0 rejected · el 0 slips, 0 rejected');
    const overflow = await page.evaluate(() => document.documentElement.scrollWidth > innerWidth);
    assert.equal(overflow, false, `horizontal scroll at ${width} px`);
    await screenshot(page, `control-${width}-${scheme}.png`);
    assert.deepEqual(page.errors, []);
    await page.context().close();
  }
});

test('small phone: STOP stays in reach; the elevation arc shows both travel limits', async () => {
  // The park elevation moves inside the narrower travel with it (a park
  // outside the travel is refused).
  assert.equal((await run.rotord.post('/api/settings',
    { 'el.min_deg': 10, 'el.max_deg': 170, 'park.el_deg': 10 })).status, 200);
  await run.rotord.advance(100);  // the controller applies new settings on its next tick
  const page = await openPage(run.browser, run.rotord.url + '/', { width: 360, height: 640 });
  await page.waitForSelector('#conn.live');
  const stop = await page.locator('#stop').boundingBox();
  assert.ok(stop.y >= 0 && stop.y + stop.height <= 640, `STOP at ${stop.y}..${stop.y + stop.height}`);
  // Two blocked wedges: below 10 and above 170.
  await until(async () => ((await page.getAttribute('#el-blocked', 'd')) || '').split('M').length === 3,
    { what: 'two blocked wedges' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
  assert.equal((await run.rotord.post('/api/settings',
    { 'el.min_deg': 0, 'el.max_deg': 180, 'park.el_deg': 0 })).status, 200);
});

test('the Wind row shows once a wind source is set (docs/care.md)', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/');
  await page.waitForSelector('#conn.live');
  assert.equal(await page.isHidden('#wind-row'), true);  // wind.source off: nothing shown
  assert.equal((await run.rotord.post('/api/settings', { 'wind.source': 'mqtt' })).status, 200);
  await run.rotord.advance(100);
  await until(async () => !(await page.isHidden('#wind-row')), { what: 'the Wind row' });
  assert.equal(await page.textContent('#wind'), 'no reading yet, calm (stows at 20 m/s), 0 stows');
  assert.equal(await page.isHidden('#wind-override'), true);  // nothing stowed to override
  assert.deepEqual(page.errors, []);
  await page.context().close();
  assert.equal((await run.rotord.post('/api/settings', { 'wind.source': 'off' })).status, 200);
});

test('clicking the rose moves the rotator and the displayed azimuth follows', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/');
  await page.waitForSelector('#conn.live');
  const box = await page.locator('#rose').boundingBox();
  // East of the centre, inside the face: azimuth 90.
  await page.mouse.click(box.x + box.width / 2 + box.width * 0.3, box.y + box.height / 2);
  await until(async () => (await run.rotord.status()).az.target_deg !== null, { what: 'a target' });
  assert.ok(Math.abs((await run.rotord.status()).az.target_deg - 90) <= 2);
  await run.rotord.untilAdvancing(async () => {
    const s = await run.rotord.status();
    return !s.moving && Math.abs(s.az.position_deg - 90) <= 1.5;
  }, { stepMs: 1000, what: 'arrival at 90' });
  await until(async () => Math.abs((await displayedAz(page)) - 90) <= 1.5, { what: 'display at 90' });
  // The wear odometer counted the move, and the page shows what the API says
  // (docs/care.md).
  const odo = (await run.rotord.status()).odometer.az;
  assert.ok(odo.starts >= 1 && odo.turned_deg >= 100, JSON.stringify(odo));
  await until(async () => (await page.textContent('#wear')).startsWith(
    `az ${odo.starts} starts, ${(odo.run_s / 3600).toFixed(1)} h, ${odo.turned_deg}°, ` +
    `${odo.relay_switchings} relay, 0 faults`), { what: 'the wear line' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

async function holdCw(page) {
  const b = await page.locator('.hold [data-dir="cw"]').boundingBox();
  await page.mouse.move(b.x + b.width / 2, b.y + b.height / 2);
  await page.mouse.down();
}

test('holding CW moves, releasing stops', async () => {
  const page = await openLive(run.rotord.url + '/');
  const start = (await run.rotord.status()).az.position_deg;
  await holdCw(page);
  await until(async () => (await run.rotord.status()).az.jogging, { what: 'jogging' });
  // The G-5500 turns about 6 deg/s. Advanced in steps, one per renewal of
  // the page: the dead-man runs on the network's clock, which the manual
  // clock moves too, and the page renews it on its own timer (a real
  // browser's setInterval, which no daemon clock drives). Each step waits for
  // the next renewal's answer, so a renewal lands within every 700 ms hold
  // whatever the machine's pace; the assertions below check the outcome.
  const renewal = (r) => r.url().endsWith('/api/move') && r.request().method() === 'POST';
  for (let step = 0; step < 30; step++) {
    await run.rotord.advance(100);
    await page.waitForResponse(renewal, { timeout: 15000 });
  }
  const held = await run.rotord.status();
  assert.equal(held.az.jogging, true, 'jogging while held');
  assert.ok(held.az.position_deg > start + 5, `moved CW: ${start} -> ${held.az.position_deg}`);
  await page.mouse.up();
  await until(async () => !(await run.rotord.status()).az.jogging, { timeout: 1000, what: 'stop on release' });
  await run.rotord.untilAdvancing(async () => !(await run.rotord.status()).moving, { what: 'standstill' });
  await until(async () => Math.abs((await displayedAz(page)) - (await run.rotord.status()).az.position_deg) < 1,
    { what: 'display follows' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('closing the page while holding stops the motor', async () => {
  const page = await openLive(run.rotord.url + '/');
  await holdCw(page);
  await until(async () => (await run.rotord.status()).az.jogging, { what: 'jogging' });
  await page.context().close();
  await until(async () => !(await run.rotord.status()).az.jogging, { timeout: 1500, what: 'stop after close' });
});

test('a stalled network stops the motor (dead-man, no stop message)', async () => {
  const page = await openLive(run.rotord.url + '/');
  await holdCw(page);
  await until(async () => (await run.rotord.status()).az.jogging, { what: 'jogging' });
  await page.context().setOffline(true);  // renewals and the stop on release are lost
  // Wall time on purpose: the dead-man runs on the transport's clock, and
  // its timeout is the thing under test.
  const t0 = Date.now();
  await until(async () => !(await run.rotord.status()).az.jogging, { timeout: 2000, what: 'dead-man stop' });
  assert.ok(Date.now() - t0 <= 1500, `stopped after ${Date.now() - t0} ms`);
  await page.context().close();
});

test('settings: a bad value shows its error, a good one survives a restart', async () => {
  let page = await openPage(run.browser, run.rotord.url + '/settings.html', { width: 1280, height: 900 });
  await page.waitForSelector('#f-az\\.max_deg');
  await page.waitForSelector('#cal-az');
  await screenshot(page, 'settings-1280.png');
  await page.fill('#f-az\\.max_deg', '9999');
  await page.click('#save');
  const error = page.locator('.field.invalid .error');
  await error.first().waitFor();
  assert.match(await error.first().textContent(), /outside the allowed range/);
  assert.match(await page.textContent('#msg'), /outside the allowed range/);
  const unchanged = (await request(run.rotord.url + '/api/settings')).body;
  assert.equal(unchanged['az.max_deg'], 450);

  await page.fill('#f-az\\.max_deg', '450');
  await page.fill('#f-park\\.az_deg', '77');
  await page.click('#save');
  await until(async () => (await page.textContent('#msg')).includes('saved'), { what: 'saved' });
  assert.equal(await page.locator('.field.invalid').count(), 0);
  // Chromium logs the refused POST (422) as a failed resource: that one is expected.
  assert.deepEqual(page.errors.filter((e) => !/status of 422/.test(e)), []);
  await page.context().close();

  await run.rotord.stop();
  await run.rotord.start();
  page = await openPage(run.browser, run.rotord.url + '/settings.html', { width: 360, height: 780, colorScheme: 'dark' });
  await page.waitForSelector('#f-park\\.az_deg');
  await until(async () => (await page.inputValue('#f-park\\.az_deg')) === '77', { what: 'persisted value' });
  await screenshot(page, 'settings-360-dark.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('calibration: "set as low point" writes the live raw reading', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/settings.html');
  await page.waitForSelector('#cal-az-lo');
  await until(async () => /\d/.test(await page.textContent('#cal-az-raw')), { what: 'a live raw reading' });
  const raw = (await run.rotord.status()).az.raw;
  await page.fill('#cal-az-deg', '0');
  await page.click('#cal-az-lo');
  await until(async () => (await page.textContent('#msg')).includes('low point set'), { what: 'cal set' });
  const s = (await request(run.rotord.url + '/api/settings')).body;
  assert.ok(Math.abs(s['az.pot_cal_lo_counts'] - raw) < 20, `${s['az.pot_cal_lo_counts']} vs ${raw}`);
  assert.equal(s['az.pot_cal_lo_deg'], 0);
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('settings: a stored Wi-Fi password shows masked and an untouched save keeps it', async () => {
  const post = (doc) => request(run.rotord.url + '/api/settings', 'POST', JSON.stringify(doc));
  assert.equal((await post({ 'wifi.password': 'hunter2-wpa2-pass' })).status, 200);
  const page = await openPage(run.browser, run.rotord.url + '/settings.html');
  const field = '#f-wifi\\.password';
  // The Wi-Fi is the Pico W's: shown in the simulator only when asked for.
  await page.waitForSelector(field, { state: 'attached' });
  assert.equal(await page.isVisible(field), false);
  await page.check('#show-all');
  await page.waitForSelector(field);
  assert.equal(await page.getAttribute(field, 'type'), 'password');
  await until(async () => (await page.inputValue(field)) === '********', { what: 'masked password' });
  assert.ok(!(await page.content()).includes('hunter2'));
  await page.fill('#f-wifi\\.ssid', 'Shack Net');
  await page.click('#save');
  await until(async () => (await page.textContent('#msg')).includes('saved'), { what: 'saved' });
  const s = (await request(run.rotord.url + '/api/settings')).body;
  assert.equal(s['wifi.ssid'], 'Shack Net');
  assert.equal(s['wifi.password'], '********', 'still stored, still hidden');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});
