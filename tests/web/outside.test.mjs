// What testing rotord from outside found in the web pages (issue 23), in the
// real browser (Debian's chromium, playwright-core) against `rotord --sim
// g5500 --clock manual`: number fields that refuse what is not a number
// beside the field, dependent settings refused with both names, the speed
// slider on a one-speed relay drive, the station page with MQTT off, and the
// Track page refusing passes and tracks in words until the station's
// position is set, with a link to the setting.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import {
  ISS, openPage, request, rotordAndBrowser, screenshot, until,
} from './harness.mjs';

const run = rotordAndBrowser({ clock: 'manual', extraArgs: ['--utc-start', '2019-12-09T19:15:00Z'] });

const settings = async () => (await request(run.rotord.url + '/api/settings')).body;

/** Fills one settings field, saves, and returns the error shown beside it. */
async function saveField(page, key, text) {
  const id = '#f-' + key.replace('.', '\\.');
  await page.fill(id, text);
  await page.click('#save');
  const row = page.locator(`.field:has(${id})`);
  await until(async () => (await row.getAttribute('class')).includes('invalid'),
    { what: `${key} marked` });
  return row.locator('.error').textContent();
}

test('settings: a number field refuses a decimal comma and a word beside the field; a locator is understood', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/settings.html');
  await page.waitForSelector('#f-station\\.lat_deg');
  for (const [typed, why] of [['12,5', /12\.5 \(a point, not a comma\)/], ['north', /not a number/]]) {
    assert.match(await saveField(page, 'station.lat_deg', typed), why);
    assert.match(await page.textContent('#msg'), /not saved/);
    // What was typed stays, for the user to correct; nothing was saved.
    assert.equal(await page.inputValue('#f-station\\.lat_deg'), typed);
    assert.equal((await settings())['station.lat_deg'], 0);
  }
  // A Maidenhead locator typed where a position is asked for (issue 24):
  // both fields take its square's centre, saved as numbers.
  await page.fill('#f-station\\.lat_deg', 'JO62qm');
  assert.equal(await page.locator('.field:has(#f-station\\.lat_deg) .error').textContent(), '');
  await page.click('#save');
  await until(async () => (await page.textContent('#msg')).includes('saved'), { what: 'saved' });
  assert.equal(await page.inputValue('#f-station\\.lat_deg'), '52.5208');
  assert.equal(await page.inputValue('#f-station\\.lon_deg'), '13.375');
  assert.equal((await settings())['station.lat_deg'], 52.5208);
  assert.equal((await settings())['station.lon_deg'], 13.375);
  // Only a latitude again, as the track test below expects.
  await page.fill('#f-station\\.lat_deg', '52.5');
  await page.fill('#f-station\\.lon_deg', '0');
  await page.click('#save');
  await until(async () => (await settings())['station.lon_deg'] === 0, { what: 'saved' });
  assert.equal((await settings())['station.lat_deg'], 52.5);
  assert.equal(await page.locator('.field.invalid').count(), 0);
  await screenshot(page, 'outside-settings-numbers.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('settings: a park azimuth outside the travel is refused, naming both settings', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/settings.html');
  await page.waitForSelector('#f-park\\.az_deg');
  const why = await saveField(page, 'park.az_deg', '500');
  assert.match(why, /park\.az_deg 500 is outside the azimuth travel az\.min_deg\.\.az\.max_deg \(0\.\.450\)/);
  assert.equal((await settings())['park.az_deg'], 0);
  // The REST API and the protocols refuse it the same way.
  const r = await run.rotord.post('/api/settings', { 'az.max_deg': 300, 'park.az_deg': 350 });
  assert.equal(r.status, 422);
  assert.match(r.body.errors['park.az_deg'], /az\.max_deg/);
  assert.match(r.body.errors['az.max_deg'], /park\.az_deg/);
  assert.deepEqual(page.errors.filter((e) => !/status of 422/.test(e)), []);
  await page.context().close();
});

test('control: on a one-speed relay drive the speed slider says speed does nothing', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/', { width: 390, height: 844 });
  await page.waitForSelector('#conn.live');
  await until(async () => !(await page.isHidden('#speed-note')), { what: 'the note' });
  assert.equal(await page.isDisabled('#speed'), true);
  assert.match(await page.textContent('#speed-note'), /one\s+speed/);
  assert.equal(await page.getAttribute('#speed-note a', 'href'), 'settings.html#f-az.drive');
  assert.equal((await run.rotord.status()).speed_applies, false);
  await screenshot(page, 'outside-control-one-speed-390.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('station page with MQTT off: says why, with no 404 in the console', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/station.html', { width: 390, height: 844 });
  await until(async () => /MQTT is off/.test(await page.textContent('#msg')), { what: 'the reason' });
  assert.deepEqual(page.errors, []);  // a 404 shows here as "Failed to load resource"
  const st = await request(run.rotord.url + '/api/station');
  assert.equal(st.status, 200);
  assert.equal(st.body.available, false);
  await page.context().close();
});

test('track: no passes and no track until the station position is set, said in words', async () => {
  // The position typed above is only a latitude: 0 N 0 E is "not set", so
  // start from there again.
  assert.equal((await run.rotord.post('/api/settings', { 'station.lat_deg': 0 })).status, 200);
  const put = await request(run.rotord.url + '/api/tle', 'PUT', ISS);
  assert.equal(put.status, 200, JSON.stringify(put.body));
  const page = await openPage(run.browser, run.rotord.url + '/track.html');
  await until(async () => (await page.inputValue('#object')) === '25544', { what: 'object list' });
  await until(async () => /position is not set/.test(await page.textContent('#msg')),
    { what: 'passes refused' });
  const link = page.locator('#msg a', { hasText: 'station.lat_deg' });
  assert.equal(await link.getAttribute('href'), 'settings.html#f-station.lat_deg');
  assert.equal(await page.locator('#passes tbody tr').count(), 0);
  await page.click('#track-next');
  await until(async () => /position is not set/.test(await page.textContent('#msg')) &&
    (await page.locator('#msg a').count()) === 2, { what: 'track refused' });
  assert.equal((await run.rotord.status()).mode, 'idle');
  await screenshot(page, 'outside-track-no-station.png');
  // The link opens the settings page at that field.
  await link.click();
  await page.waitForURL(/settings\.html#f-station\.lat_deg$/);
  await until(async () => page.evaluate(() => document.activeElement &&
    document.activeElement.id === 'f-station.lat_deg'), { what: 'the field focused' });
  // Once set, the same page lists the passes.
  assert.equal((await run.rotord.post('/api/settings',
    { 'station.lat_deg': 39.86366, 'station.lon_deg': -119.17875 })).status, 200);
  await page.goto(run.rotord.url + '/track.html');
  await until(async () => /12-09 19:26:15/.test(await page.textContent('#passes')), { what: 'passes' });
  assert.deepEqual(page.errors.filter((e) => !/status of 409/.test(e)), []);
  await page.context().close();
});
