// The station page (issue 17) in the real browser (Debian's chromium,
// playwright-core): two rotords on one real Mosquitto broker (Debian
// `mosquitto`, on a free port); each one's page lists both, with a needle on
// the compass and a link to the other's panel, and shows one going offline
// when it stops.
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

import {
  cleanup, freePort, launchBrowser, openPage, Rotord, screenshot, tempDir, until,
} from './harness.mjs';

let browser;
let dir;
let broker;
const rotords = [];

before(async () => {
  dir = tempDir();
  const port = await freePort();
  const conf = path.join(dir, 'mosquitto.conf');
  writeFileSync(conf, `listener ${port} 127.0.0.1\nallow_anonymous true\n`);
  broker = spawn('mosquitto', ['-c', conf], { stdio: 'ignore' });
  for (const name of ['east', 'west']) {
    const configPath = path.join(dir, `${name}.json`);
    writeFileSync(configPath, JSON.stringify({
      'mqtt.enabled': true, 'mqtt.host': '127.0.0.1', 'mqtt.port': port,
      'mqtt.prefix': `rotord/${name}`, 'mqtt.client_id': `rotord-${name}`,
    }));
    const r = new Rotord({ configPath });
    rotords.push(r);
    // The broker may still be starting: rotord connects when it can (backoff).
    await r.start();
  }
  await until(() => rotords.every((r) => r.output.includes('mqtt: connected')),
    { timeout: 30000, what: 'both rotords on the broker' });
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  for (const r of rotords) await r.stop();
  if (broker) broker.kill('SIGKILL');
  cleanup(dir);
});

test('on a 390 px phone every column fits, State included (issue 23)', async () => {
  const [east] = rotords;
  const page = await openPage(browser, east.url + '/station.html', { width: 390, height: 844 });
  await until(async () => (await page.$$('#rotators tbody tr')).length === 2, { what: 'two rows' });
  for (const cell of await page.$$('#rotators tr > :last-child')) {
    const box = await cell.boundingBox();
    assert.ok(box && box.x >= 0 && box.x + box.width <= 390, `State column at ${box && box.x}..${box && box.x + box.width}`);
  }
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth > innerWidth);
  assert.equal(overflow, false, 'horizontal scroll at 390 px');
  await screenshot(page, 'station-390.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('each station page lists both rotords on one compass, linked to their panels', async () => {
  const [east, west] = rotords;
  const page = await openPage(browser, east.url + '/station.html');
  await until(async () => (await page.$$('#rotators tbody tr')).length === 2,
    { what: 'two rows' });
  assert.equal((await page.$$('#needles line')).length, 2);
  const link = await page.getAttribute('#rotators tr[data-prefix="rotord/west"] a', 'href');
  assert.ok(link.endsWith(`:${west.port}/`), link);
  assert.match(await page.textContent('#rotators tr[data-prefix="rotord/east"]'), /online/);
  await screenshot(page, 'station.png');

  // One stops: its last will marks it offline on the other's page.
  await west.stop();
  await until(async () => /offline/.test(
    await page.textContent('#rotators tr[data-prefix="rotord/west"]')), { what: 'west offline' });
  assert.deepEqual(page.errors, []);
  await page.context().close();
});
