// Runs a real rotord and Debian's chromium (through playwright-core, never a
// downloaded browser) for the browser tests.
import { spawn } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import http from 'node:http';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { after, before } from 'node:test';
import { chromium } from 'playwright-core';

export const ROTORD = process.env.ROTORD ?? path.resolve(import.meta.dirname, '../../build/rotord');
export const ARTIFACTS = process.env.ROTORD_ARTIFACTS ??
  path.resolve(path.dirname(ROTORD), 'test-artifacts');
const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';

/** The ISS's elements of 2019-12-09 as a TLE text (name line and both lines). */
export const ISS = [
  'ISS (ZARYA)',
  '1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991',
  '2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482',
].join('\n');

export function freePort() {
  return new Promise((resolve, reject) => {
    const s = net.createServer();
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
    s.on('error', reject);
  });
}

export function tempDir() {
  return mkdtempSync(path.join(os.tmpdir(), 'rotord-web-'));
}

/**
 * A running `rotord --sim g5500` on free loopback ports: `--speedup 10`, or
 * with `clock: 'manual'` controller time that moves only by advance().
 */
export class Rotord {
  constructor({ configPath, speedup = 10, profile = 'g5500', clock = 'wall', extraArgs = [] } = {}) {
    this.configPath = configPath;
    this.extraArgs = extraArgs;  // e.g. ['--utc-start', '2019-12-09T19:15:00Z']
    this.speedup = speedup;
    this.profile = profile;
    this.clock = clock;
    this.output = '';
  }

  async start() {
    // A port found free can be taken by another test before rotord binds
    // it: then try other ports (a restart keeps the port it had).
    const chosen = this.port === undefined;
    for (let attempt = 1; ; attempt++) {
      if (chosen) this.port = await freePort();
      const from = this.output.length;
      try {
        await this.spawn();
        return this;
      } catch (e) {
        if (!chosen || attempt >= 5 || !this.output.slice(from).includes('Address already in use')) throw e;
      }
    }
  }

  async spawn() {
    const timing = this.clock === 'manual' ? ['--clock', 'manual'] : ['--speedup', String(this.speedup)];
    const args = ['--sim', this.profile, ...timing, '--bind', '127.0.0.1',
      '--web-port', String(this.port), '--wrc-port', '0', '--rotctld-port', '0',
      '--gs232-port', '0', '--easycomm-port', '0', '--config', this.configPath, ...this.extraArgs];
    this.proc = spawn(ROTORD, args, { stdio: ['pipe', 'pipe', 'pipe'] });
    this.clockSeen = 0;
    const from = this.output.length; // a restart's own 'ready', not the last run's
    const ready = new Promise((resolve, reject) => {
      const onData = (d) => {
        this.output += d;
        if (this.output.slice(from).includes('rotord: ready')) resolve();
      };
      this.proc.stdout.on('data', onData);
      this.proc.stderr.on('data', onData);
      this.proc.on('exit', (code) => reject(new Error(`rotord exited (${code}): ${this.output}`)));
      // A bound for liveness only (the daemon, another process, starts on the
      // wall clock); 'ready' ends the wait as soon as it is printed.
      setTimeout(() => reject(new Error(`rotord not ready: ${this.output}`)), 15000);
    });
    await ready;
    this.url = `http://127.0.0.1:${this.port}`;
  }

  async stop() {
    if (!this.proc || this.proc.exitCode !== null) return;
    const exited = new Promise((resolve) => this.proc.on('exit', resolve));
    this.proc.kill('SIGTERM');
    await exited;
  }

  /** --clock manual: runs `ms` of controller time; resolves with the new time. */
  async advance(ms) {
    const from = this.output.length;
    this.proc.stdin.write(`advance ${ms}\n`);
    const line = await until(() => {
      const m = /rotord: clock (\d+)\n/.exec(this.output.slice(from));
      return m && Number(m[1]);
    }, { interval: 5, what: `clock advance ${ms}` });
    return line;
  }

  /** until() that advances controller time by `stepMs` between the checks. */
  async untilAdvancing(fn, { stepMs = 500, ...options } = {}) {
    return until(async () => (await fn()) || (await this.advance(stepMs), false), options);
  }

  async status() {
    return (await request(`${this.url}/api/status`)).body;
  }

  async post(p, body) {
    return request(this.url + p, 'POST', JSON.stringify(body ?? {}));
  }
}

/**
 * One HTTP request on its own connection. Not fetch(): it reuses idle
 * keep-alive connections, and rotord closes an idle one after 5 s, so a
 * reused connection can be closed just as a request goes out ("fetch failed").
 */
export function request(url, method = 'GET', body = undefined) {
  return new Promise((resolve, reject) => {
    const headers = body === undefined ? {} : { 'Content-Type': 'application/json',
      'Content-Length': Buffer.byteLength(body) };
    const req = http.request(url, { method, headers, agent: false }, (res) => {
      let text = '';
      res.setEncoding('utf8');
      res.on('data', (chunk) => { text += chunk; });
      res.on('end', () => {
        let parsed = null;
        try { parsed = JSON.parse(text); } catch { parsed = null; }
        resolve({ status: res.statusCode, body: parsed });
      });
    });
    req.on('error', reject);
    if (body !== undefined) req.write(body);
    req.end();
  });
}

export async function launchBrowser() {
  return chromium.launch({
    executablePath: CHROMIUM,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking'],
  });
}

/** A page that records console errors and uncaught exceptions. */
export async function openPage(browser, url, { width = 1280, height = 900, colorScheme = 'light' } = {}) {
  const context = await browser.newContext({ viewport: { width, height }, colorScheme,
    hasTouch: width < 500, isMobile: false });
  const page = await context.newPage();
  page.errors = [];
  page.on('console', (m) => { if (m.type() === 'error') page.errors.push(m.text()); });
  page.on('pageerror', (e) => page.errors.push(String(e)));
  await page.goto(url);
  return page;
}

export async function screenshot(page, name) {
  mkdirSync(ARTIFACTS, { recursive: true });
  await page.screenshot({ path: path.join(ARTIFACTS, name), fullPage: true });
}

/**
 * Polls fn() until it returns a truthy value or the time runs out: the one
 * wall-clock poll of the browser tests. For what runs on the wall clock and
 * no daemon clock moves (the browser's own timers and rendering, another
 * process, the login budget of a rotord without a manual clock); what runs on
 * the controller's or the network's clock is advanced instead
 * (untilAdvancing). `timeout` is for liveness only, never a timing.
 */
export async function until(fn, { timeout = 15000, interval = 100, what = 'condition' } = {}) {
  const end = Date.now() + timeout;
  let last;
  while (Date.now() < end) {
    last = await fn();
    if (last) return last;
    await new Promise((r) => setTimeout(r, interval));
  }
  throw new Error(`timed out waiting for ${what} (last: ${JSON.stringify(last)})`);
}

export function cleanup(dir) {
  rmSync(dir, { recursive: true, force: true });
}

/**
 * A test file's one rotord (options as for Rotord, its settings file in a
 * fresh temporary folder) and one browser: started before the file's first
 * test, stopped after its last. `ready(rotord)` runs once the daemon is up,
 * before the browser starts. Returns { rotord, browser, dir }, filled in by
 * then.
 */
export function rotordAndBrowser(options = {}, ready = async () => {}) {
  const run = {};
  before(async () => {
    run.dir = tempDir();
    run.rotord = await new Rotord({ configPath: path.join(run.dir, 'settings.json'), ...options }).start();
    await ready(run.rotord);
    run.browser = await launchBrowser();
  });
  after(async () => {
    if (run.browser) await run.browser.close();
    if (run.rotord) await run.rotord.stop();
    cleanup(run.dir);
  });
  return run;
}
