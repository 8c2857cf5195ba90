// The settings page in the owner's words (issue 24), in the real browser on
// a phone (390x844) and a desktop (1280x900): a search finds a setting by
// its words, the settings that do not apply to this platform or drive are
// hidden (and come back live when the drive is changed in the form), an
// edit is marked unsaved and the result of Save appears in view, and a
// number field refuses what is not a number as it is typed. Prints the
// page's height on both; screenshots in test-artifacts/.
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { cleanup, launchBrowser, openPage, request, Rotord, screenshot, tempDir, until } from './harness.mjs';

let browser;
let dir;
let rotord;

before(async () => {
  dir = tempDir();
  // The simulated G-5500: az/el, relays, pots. Not a Pico W, not a Pi.
  rotord = await new Rotord({ configPath: path.join(dir, 'settings.json'), profile: 'g5500' }).start();
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  if (rotord) await rotord.stop();
  cleanup(dir);
});

const visible = (page, key) => page.isVisible('#f-' + key.replaceAll('.', '\\.'));
const row = (page, key) => page.locator(`.field:has(#f-${key.replaceAll('.', '\\.')})`);

/** Whether the element is inside the viewport now. */
async function inView(page, selector) {
  return page.$eval(selector, (e) => {
    const r = e.getBoundingClientRect();
    return r.height > 0 && r.top >= 0 && r.bottom <= window.innerHeight;
  });
}

for (const [width, height] of [[390, 844], [1280, 900]]) {
  test(`settings at ${width}x${height}: words, what applies, unsaved, the result in view, numbers`, async () => {
    const page = await openPage(browser, rotord.url + '/settings.html', { width, height });
    await page.waitForSelector('#f-az\\.tolerance_deg');
    const size = await page.evaluate(() => ({
      height: document.documentElement.scrollHeight,
      fields: [...document.querySelectorAll('.field')].filter((e) => e.checkVisibility()).length,
      all: document.querySelectorAll('.field').length,
    }));
    console.log(`settings page at ${width}x${height}: ${size.height} px tall, ` +
      `${size.fields} of ${size.all} settings shown`);
    await screenshot(page, `settings-words-${width}x${height}.png`);

    // Every row has its label and its help (the table's, from
    // /settings_help.js), none shown by its key alone.
    const missing = await page.evaluate(async () => {
      const schema = await (await fetch('/api/settings/schema')).json();
      return schema.settings.filter((d) => !d.label || d.label === d.key || !rotordSettingsHelp[d.key])
        .map((d) => d.key);
    });
    assert.deepEqual(missing, []);
    assert.match(await row(page, 'az.tolerance_deg').locator('.help').textContent(), /within this distance/);
    // The owner's words, the key small beside them, the owner's groups.
    assert.match(await row(page, 'az.tolerance_deg').locator('label').textContent(),
      /^Close enough to the target\s*az\.tolerance_deg$/);
    const legends = await page.$$eval('#groups legend', (l) => l.map((e) => e.textContent));
    assert.deepEqual(legends.slice(0, 2), ['Rotator', 'Wiring']);

    // Not for this platform: the Pico W's pins, the Pi's lines, the Wi-Fi.
    // Not for this drive and sensor: the H-bridge's PWM, the MA3, the
    // magnetometer. Rarely changed: under Advanced, closed.
    for (const key of ['pins.az_cw', 'gpiod.az_cw', 'wifi.ssid', 'az.pwm_slow_duty', 'az.ma3_zero_deg',
      'mag.chip', 'az.slow_zone_deg']) {
      assert.equal(await visible(page, key), false, key);
    }
    assert.equal(await page.isVisible('#groups fieldset:has(legend:text-is("Wiring"))'), false);
    assert.equal(await visible(page, 'az.min_dwell_ms'), false, 'advanced, closed');
    assert.equal(await visible(page, 'el.tolerance_deg'), true, 'the G-5500 has an elevation axis');

    // A search by the owner's words, not the key.
    await page.fill('#search', 'close enough');
    await until(async () => !(await visible(page, 'park.az_deg')), { what: 'search applied' });
    assert.equal(await visible(page, 'az.tolerance_deg'), true);
    assert.equal(await visible(page, 'el.tolerance_deg'), true);
    assert.match(await page.textContent('#found'), /^2 found$/);
    // Advanced rows are found too: their section opens.
    await page.fill('#search', 'relay rest');
    await until(() => visible(page, 'az.min_dwell_ms'), { what: 'an advanced row found' });
    // A setting that does not apply here is not shown, but counted.
    await page.fill('#search', 'slow zone');
    await until(async () => /2 more do not apply/.test(await page.textContent('#found')), { what: 'counted' });
    assert.equal(await visible(page, 'az.slow_zone_deg'), false);
    await page.check('#show-all');
    assert.equal(await visible(page, 'az.slow_zone_deg'), true);
    await page.uncheck('#show-all');
    await page.fill('#search', '');
    // The search over, the Advanced parts it opened close again.
    assert.equal(await visible(page, 'az.min_dwell_ms'), false);

    // What applies follows the form as it stands: an H-bridge shows its
    // PWM duties and its slow zone before anything is saved.
    await page.selectOption('#f-az\\.drive', 'hbridge');
    assert.equal(await visible(page, 'az.pwm_slow_duty'), true);
    assert.equal(await visible(page, 'az.slow_zone_deg'), true);
    assert.match(await page.textContent('#unsaved'), /^1 unsaved$/);
    assert.match(await row(page, 'az.drive').getAttribute('class'), /changed/);
    await page.selectOption('#f-az\\.drive', 'relay');
    assert.equal(await visible(page, 'az.pwm_slow_duty'), false);
    assert.equal(await page.textContent('#unsaved'), '');

    // A number field refuses a decimal comma as it is typed, beside it.
    await page.fill('#f-az\\.tolerance_deg', '1,5');
    assert.match(await row(page, 'az.tolerance_deg').locator('.error').textContent(), /1\.5 \(a point, not a comma\)/);
    assert.match(await row(page, 'az.tolerance_deg').getAttribute('class'), /invalid/);
    await page.click('#save');
    await until(async () => /not saved/.test(await page.textContent('#msg')), { what: 'refused' });
    assert.ok(await inView(page, '#msg'), 'the refusal is in view');
    assert.equal((await request(rotord.url + '/api/settings')).body['az.tolerance_deg'], 1);
    await page.fill('#f-az\\.tolerance_deg', '1');
    assert.equal(await row(page, 'az.tolerance_deg').locator('.error').textContent(), '');

    // An edit far down the page: marked unsaved, and Save's result appears
    // where the owner is, not below the last group.
    const park = width === 390 ? 'track.min_el_deg' : 'station.alt_m';
    const parkField = `#f-${park.replace('.', '\\.')}`;
    await page.$eval(parkField, (e) => e.scrollIntoView({ block: 'center' }));
    await page.fill(parkField, '5');
    assert.match(await row(page, park).getAttribute('class'), /changed/);
    assert.match(await page.textContent('#unsaved'), /^1 unsaved$/);
    assert.ok(await inView(page, '#save'), 'Save is in reach');
    await page.click('#save');
    // Not /saved/: the refusal above ("not saved: ...") is still shown until
    // the save's answer replaces it; the page reloads the values after it.
    await until(async () => /^saved/.test(await page.textContent('#msg')), { what: 'saved' });
    assert.ok(await inView(page, '#msg'), 'the result is in view');
    assert.ok(await inView(page, parkField), 'the page did not jump away');
    await until(async () => (await page.textContent('#unsaved')) === '', { what: 'nothing unsaved once reloaded' });
    assert.doesNotMatch(await row(page, park).getAttribute('class'), /changed/);
    assert.equal((await request(rotord.url + '/api/settings')).body[park], 5);
    await screenshot(page, `settings-words-saved-${width}x${height}.png`);
    // The refused save's 422 is not one: the number never left the page.
    assert.deepEqual(page.errors, []);
    await page.context().close();
  });
}
