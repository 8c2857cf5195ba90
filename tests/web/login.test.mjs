// Access control in the real page (Debian's chromium, playwright-core): with
// a web password set, every page sends the browser to the login page; a
// wrong password is refused there, the right one gives an HttpOnly,
// SameSite=Strict session cookie and the control page; STOP works without
// a login; logging out ends the session; the control lock shows who has it.
import assert from 'node:assert/strict';
import path from 'node:path';
import { test } from 'node:test';

import {
  ARTIFACTS, openPage, request, rotordAndBrowser, screenshot, until,
} from './harness.mjs';

const PASSWORD = 'correct horse battery';
const run = rotordAndBrowser({}, async (rotord) => {
  // Off by default: one call turns it on.
  assert.equal((await rotord.post('/api/password', { password: PASSWORD })).status, 200);
});

async function logIn(page, password) {
  await page.fill('#password', password);
  await page.click('#submit');
}

// A fresh run.browser (no device cookie) shares the strangers' budget of
// checked guesses (10 a minute, docs/security.md): the tests before this one
// may have spent it, so the owner waits as a person would and tries again.
async function logInAsOwner(page) {
  // The guess budget refills on the daemon's wall clock (this run.rotord has no
  // manual clock): until() retries a second apart, as a person would, until
  // the login succeeds; the pace never decides the result.
  await until(async () => {
    await logIn(page, PASSWORD);
    await until(async () => new URL(page.url()).pathname !== '/login.html' ||
      /too many|wrong|error/.test(await page.textContent('#msg')), { what: 'login answered' });
    if (new URL(page.url()).pathname === '/login.html') {
      assert.match(await page.textContent('#msg'), /too many/);
      return false;
    }
    // The refused tries' 429s are the budget at work, not errors of the page.
    const others = page.errors.filter((e) => !e.includes('status of 429'));
    page.errors.splice(0, page.errors.length, ...others);
    return true;
  }, { timeout: 60000, interval: 1000, what: 'the owner got in' });
}

test('a page asked for without a login goes to the login page; STOP works there', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/settings.html');
  assert.equal(new URL(page.url()).pathname, '/login.html');
  assert.equal((await request(run.rotord.url + '/api/status')).status, 401);
  assert.equal((await run.rotord.post('/api/goto', { az: 200 })).status, 401);
  await page.click('#stop');
  await until(async () => (await page.textContent('#msg')) === 'stopped', { what: 'stopped' });
  await screenshot(page, 'login.png');
  assert.deepEqual(page.errors, []);
  await page.context().close();
});

test('a wrong password is refused on the page; the right one opens the control page', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/');
  await logIn(page, 'not the password');
  await until(async () => (await page.textContent('#msg')) === 'wrong password', { what: 'refusal' });
  assert.equal(new URL(page.url()).pathname, '/login.html');
  await logIn(page, PASSWORD);
  await page.waitForURL(run.rotord.url + '/');
  await page.waitForSelector('#conn.live');
  const [cookie] = await page.context().cookies();
  assert.equal(cookie.name, 'rotord_session');
  assert.equal(cookie.httpOnly, true);
  assert.equal(cookie.sameSite, 'Strict');
  assert.match(cookie.value, /^[0-9a-f]{32}$/);
  // No script on the page can read it.
  assert.equal(await page.evaluate(() => document.cookie), '');
  assert.equal(await page.isVisible('#logout'), true);
  // The page's failed resource loads before the login are not errors of this page.
  assert.deepEqual(page.errors.filter((e) => !e.includes('401')), []);
  await page.context().close();
});

test('the control lock: taken on the page, others are read-only, released on the page', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/');
  await logInAsOwner(page);
  await page.waitForSelector('#conn.live');
  await until(async () => page.isVisible('#lock-button'), { what: 'lock button' });
  await page.click('#lock-button');
  await until(async () => (await page.textContent('#lock-info')).startsWith('you have control'),
    { what: 'lock taken' });
  // A second run.browser, logged in too, is read-only while the first holds it.
  const other = await openPage(run.browser, run.rotord.url + '/');
  await logInAsOwner(other);
  await other.waitForSelector('#conn.live');
  await until(async () => (await other.textContent('#lock-info')).startsWith('locked by web session'),
    { what: 'lock shown to the other' });
  const refused = await other.evaluate(() => fetch('/api/goto', { method: 'POST',
    headers: { 'Content-Type': 'application/json' }, body: '{"az": 100}' }).then((r) => r.status));
  assert.equal(refused, 423);
  const stopped = await other.evaluate(() => fetch('/api/stop', { method: 'POST' }).then((r) => r.status));
  assert.equal(stopped, 200);
  await screenshot(other, 'locked-by-other.png');
  await page.click('#lock-button');
  await until(async () => (await page.textContent('#lock-info')) === '', { what: 'lock released' });
  await page.context().close();
  await other.context().close();
});

test('logging out ends the session', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/');
  await logInAsOwner(page);
  await page.waitForSelector('#conn.live');
  await page.click('#logout');
  await page.waitForURL(run.rotord.url + '/login.html');
  const status = await page.evaluate(() => fetch('/api/status').then((r) => r.status));
  assert.equal(status, 401);
  await page.context().close();
});

test('the settings page makes a token, shows it once, and lists it by name', async () => {
  const page = await openPage(run.browser, run.rotord.url + '/');
  await logInAsOwner(page);
  await page.waitForSelector('#conn.live');
  await page.goto(run.rotord.url + '/settings.html');
  await page.waitForSelector('#token-create');
  // The hashes are not form fields.
  assert.equal(await page.locator('[data-key="web.password"]').count(), 0);
  assert.equal(await page.locator('[data-key="web.token_1"]').count(), 0);
  await page.fill('#token-name', 'logger');
  await page.selectOption('#token-scope', 'read');
  await page.click('#token-create');
  await until(async () => /rtd_[0-9a-f]{32}/.test(await page.textContent('#new-token')),
    { what: 'the new token' });
  const token = /rtd_[0-9a-f]{32}/.exec(await page.textContent('#new-token'))[0];
  await until(async () => (await page.textContent('#tokens')).includes('logger (read)'),
    { what: 'the token listed' });
  await page.locator('#access').screenshot({ path: path.join(ARTIFACTS, 'settings-access.png') });
  // It works from a script, read-only; the page never shows it again.
  const status = await new Promise((resolve) => {
    import('node:http').then(({ default: http }) => {
      http.get(run.rotord.url + '/api/status', { headers: { Authorization: `Bearer ${token}` } },
        (res) => { res.resume(); resolve(res.statusCode); });
    });
  });
  assert.equal(status, 200);
  await page.reload();
  await page.waitForSelector('#token-create');
  assert.equal((await page.content()).includes(token), false);
  assert.deepEqual(page.errors.filter((e) => !e.includes('401')), []);
  await page.context().close();
});
