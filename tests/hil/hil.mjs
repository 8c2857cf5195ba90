// make hil: the Pico W firmware image on an emulated RP2040 (rp2040js), the
// rotator played on its pins by the simulator's plant, real clients on a pty
// bridged to the USB protocol port. Each scenario boots a fresh chip.
//
//   ROTORD_RP2040_BOOTROM=<rp2040js>/demo/bootrom.ts node hil.mjs [--only a,b] [--verbose]
//
// Environment: ROTORD_HIL_IMAGE (default <root>/build-pico/rotord_pico_w.elf),
// ROTORD_HIL_PLANT (default <root>/build/tests/hil/rotord_hil_plant),
// ROTORD_HIL_OUT (default <root>/build/bench/hil_<board>.json: the figures bench/run.py reports).
// Exit status 0 when every scenario passed. Results are read on emulated
// time only; the wall clock matters only to the clients' own timeouts.
import { execFile } from 'node:child_process';
import { closeSync, constants, existsSync, mkdirSync, openSync, readSync, writeFileSync, writeSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Board, loadBootrom } from './lib/board.mjs';
import { PtyBridge } from './lib/bridge.mjs';
import { readSettings } from './lib/flash.mjs';
import { pinDefaults } from './lib/pins.mjs';
import { Plant } from './lib/plant.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = process.env.ROTORD_ROOT ?? join(here, '../..');
const args = process.argv.slice(2);
const verbose = args.includes('--verbose');
const onlyArg = args.find((a) => a.startsWith('--only='))?.slice(7) ?? (args.includes('--only') ? args[args.indexOf('--only') + 1] : '');
const only = onlyArg ? onlyArg.split(',') : [];
const imagePath = process.env.ROTORD_HIL_IMAGE ?? join(root, 'build-pico/rotord_pico_w.elf');
const plantBinary = process.env.ROTORD_HIL_PLANT ?? join(root, 'build/tests/hil/rotord_hil_plant');
// pico_w or pico, from the image's name (rotord_pico_w.elf, rotord_pico.elf).
const boardName = basename(imagePath).replace(/^rotord_/, '').replace(/\.elf$/, '');
const hasWifi = boardName === 'pico_w';
const outPath = process.env.ROTORD_HIL_OUT ?? join(root, `build/bench/hil_${boardName}.json`);
const bootrom = loadBootrom(process.env.ROTORD_RP2040_BOOTROM);
const pins = pinDefaults(root);
const TICK_MS = 10;

// ---- a rig: plant, chip, pty ----

async function rig({ profile = 'g5500', drive, mag, sensor, thetaDeg, speedScale, noise, elSensor, elThetaDeg, settings = {}, pinMap = pins }) {
  // With noise, every conversion of a tick's burst (az.pot_samples, 8) gets its own.
  const potSamples = noise ? 8 : undefined;
  const plant = new Plant({ binary: plantBinary, profile, drive, mag, sensor, thetaDeg, speedScale, noise, elSensor, elThetaDeg, potSamples });
  const settingsDocument = await plant.settingsDocument(settings);
  const board = new Board({ bootrom, image: imagePath, pins: pinMap, plant, settingsDocument, echoLog: verbose });
  scenarioBoards.push(board);
  const bridge = new PtyBridge({ endpoint: board.ports[1] });
  const pty = await bridge.start();
  if (!(await board.runUntil(() => board.usbConnectedMs !== undefined, 3000)))
    throw new Error('USB did not enumerate within 3 s');
  const r = { plant, board, bridge, pty };
  r.close = async () => {
    await bridge.stop();
    plant.close();
  };
  return r;
}

/** Runs a client program while the chip runs; its stdout. */
async function client(board, file, argv, timeoutMs = 30000) {
  let done = null;
  const child = execFile(file, argv, { timeout: timeoutMs }, (err, stdout, stderr) => {
    done = { err, stdout, stderr };
  });
  void child;
  while (done === null) await board.run(2);
  if (done.err) throw new Error(`${file} ${argv.join(' ')}: exit ${done.err.code ?? done.err.signal}: ${done.stderr.trim()} ${done.stdout.trim()}`);
  if (verbose) console.log(`  $ ${file} ${argv.join(' ')} -> ${done.stdout.trim().replace(/\n/g, ' | ')}`);
  return done.stdout;
}

// A generous serial timeout: the chip answers within a tick of emulated
// time, but the machine running the emulation may be busy (the timeout is
// the wall clock's).
const rotctl = (r, model, ...cmd) =>
  client(r.board, 'rotctl', ['-m', String(model), '-r', r.pty, '-C', 'timeout=5000,retry=3', ...cmd]);

/**
 * A line-protocol client on the pty (the seed protocol, raw GS-232, the
 * console). The chip runs on emulated time, the pty and socat on the wall
 * clock: a request is only timed in emulated time once the device has it,
 * and the chip is held while a reply it sent is still on its way to the pty,
 * so a fast emulation never outruns the bytes.
 */
class LineClient {
  constructor(r, bridge = r.bridge) {
    this.r = r;
    this.bridge = bridge;
    this.fd = openSync(r.pty, constants.O_RDWR | constants.O_NOCTTY | constants.O_NONBLOCK);
    this.buf = '';
    this.readBytes = 0;
  }
  read() {
    const b = Buffer.alloc(512);
    for (;;) {
      let n = 0;
      try {
        n = readSync(this.fd, b, 0, b.length, null);
      } catch (e) {
        if (e.code === 'EAGAIN') return;
        throw e;
      }
      if (n <= 0) return;
      this.readBytes += n;
      this.buf += b.subarray(0, n).toString('latin1');
    }
  }
  /** Sends text, then runs the chip until parse(buffer) returns non-null; null after timeoutMs of emulated time. */
  async exchange(text, parse, timeoutMs) {
    // Wall-clock waits here only let the event loop move bytes between the
    // pty (socat, a real process) and the emulated CDC endpoint; the chip is
    // held meanwhile, so no length decides a result: emulated time alone
    // times the reply (timeoutMs).
    const wall = (ms) => new Promise((r) => setTimeout(r, ms));
    this.read(); // whatever is still on its way belongs to an earlier reply
    this.buf = '';
    const toDevice = this.bridge.bytesToDevice + text.length;
    const hostBase = this.bridge.bytesToHost;
    const readBase = this.readBytes;
    writeSync(this.fd, text);
    for (let i = 0; i < 5000 && this.bridge.bytesToDevice < toDevice; i++) await wall(1);
    const deadline = this.r.board.nowMs + timeoutMs;
    for (;;) {
      this.read();
      const reply = parse(this.buf);
      if (reply !== null) return reply;
      const inFlight = this.bridge.bytesToHost - hostBase - (this.readBytes - readBase);
      if (inFlight > 0) {
        await wall(1);
        continue;
      }
      if (this.r.board.nowMs >= deadline) return null;
      await this.r.board.run(1);
    }
  }
  /** One command, its one-line reply (GS-232, Easycomm, seed). */
  async send(line, timeoutMs = 500) {
    // GS-232 ends a reply in CR, the others in CR LF: the reply is the text
    // up to the first CR or LF; a lone LF first is the rest of an earlier CR LF.
    const reply = await this.exchange(
      line + '\r',
      (buf) => buf.replace(/^\n/, '').match(/^([^\r\n]*)[\r\n]/)?.[1] ?? null,
      timeoutMs,
    );
    if (verbose) console.log(`  > ${line} < ${reply}`);
    return reply;
  }
  /** The console's reply: the lines up to the first that starts with ok or error: (log lines may come between). */
  async command(line, timeoutMs = 1000) {
    const reply = await this.exchange(
      line + '\r\n',
      (buf) => {
        const lines = buf.split(/\r?\n/);
        lines.pop(); // not yet a whole line
        const last = lines.findIndex((l) => /^(ok|error:)/.test(l));
        return last >= 0 ? lines.slice(0, last + 1) : null;
      },
      timeoutMs,
    );
    if (verbose) console.log(`  console> ${line} < ${reply?.join(' | ')}`);
    return reply ?? [];
  }
  close() {
    closeSync(this.fd);
  }
}

// ---- checks ----

const angle = (r) => r.board.sensors?.thetaDeg ?? NaN;
const elAngle = (r) => r.board.sensors?.el?.thetaDeg ?? NaN;
const driving = (r) => {
  const on = (u) => u && (u.cw || u.ccw || u.pwmCw > 0 || u.pwmCcw > 0);
  return on(r.board.plantInputs()) || on(r.board.elPlantInputs());
};

/**
 * A go-to on a noisy sensor must not hunt: one start per axis that had to
 * move (none for one that did not), no reversal, and nothing more while it
 * stands at the target for `holdMs`.
 */
async function checkNoHunting(r, moved, holdMs = 2000) {
  for (const [axis, m] of Object.entries(r.board.motion)) {
    if (moved[axis] === undefined) continue;
    const want = moved[axis] ? 1 : 0;
    check(m.starts === want && m.reversals === 0, `${axis}: ${m.starts} drive start(s), ${m.reversals} reversal(s) (want ${want} and 0)`);
  }
  const before = { az: r.board.motion.az.starts, el: r.board.motion.el.starts };
  await r.board.run(holdMs);
  check(r.board.motion.az.starts === before.az && r.board.motion.el.starts === before.el && !driving(r),
    `at rest on the noisy sensor(s) for ${holdMs} ms more: no drive started`);
}

/** Waits until the axis has stood still (no drive) for 500 ms; false on timeout. */
async function settle(r, timeoutMs) {
  let quietSince = r.board.nowMs;
  return r.board.runUntil(() => {
    if (driving(r)) quietSince = r.board.nowMs;
    return r.board.nowMs - quietSince >= 500;
  }, timeoutMs, 10);
}

/** Ticks from the ADC: the pot is converted in a burst once per tick. */
function tickTimes(board, fromMs, toMs) {
  const out = [];
  let last = -1e9;
  for (const t of board.adcReads) {
    if (t < fromMs || t > toMs) continue;
    if (t - last > 1) out.push(t);
    last = t;
  }
  return out;
}

function tickStats(board, fromMs, toMs, busyCycles) {
  const ticks = tickTimes(board, fromMs, toMs);
  const periods = ticks.slice(1).map((t, i) => t - ticks[i]);
  const mean = periods.reduce((a, b) => a + b, 0) / periods.length;
  const worst = Math.max(...periods.map((p) => Math.abs(p - TICK_MS)));
  const seconds = (toMs - fromMs) / 1000;
  return {
    ticks: ticks.length,
    seconds,
    hz: 1000 / mean,
    worstDeviationUs: worst * 1000,
    cyclesPerTick: busyCycles / (seconds * 100),
    busyPercent: (busyCycles / (seconds * 125e6)) * 100,
  };
}

// ---- scenarios ----

const results = [];
const benchRows = [];
const scenarioBoards = []; // the chips the running scenario booted (their heap is reported)
const heapRows = [];

function check(ok, what) {
  if (!ok) throw new Error(what);
  console.log(`    ok  ${what}`);
}

const scenarios = {
  /** No answer from the Wi-Fi chip (Pico W; the plain Pico has none): USB and the control go on, the log says why; the tick rate and its cost. */
  async 'no-wifi-tick'() {
    const r = await rig({ thetaDeg: 200 });
    try {
      if (hasWifi) {
        const line = await r.board.waitForLog(/Wi-Fi|network/i, 1000);
        check(line && /does not answer|without network/.test(line.text), `log: "${line?.text}"`);
      } else {
        await r.board.run(200);
        check(!r.board.logLines.some((l) => /Wi-Fi|CYW43/.test(l.text)), 'plain Pico: no Wi-Fi in the log');
      }
      check(!r.board.logLines.some((l) => /access point|on port \d+/.test(l.text)), 'no access point or TCP port claimed');
      const p = (await rotctl(r, 603, 'p')).trim().split('\n').map(Number);
      check(Math.abs(p[0] - 200) < 0.6, `rotctl -m 603 p: ${p[0]} (plant 200.0)`);
      // The control tick, standing still, over 2 s of emulated time.
      const from = r.board.nowMs + 10;
      const cycles0 = r.board.busyCycles;
      await r.board.run(2000);
      const s = tickStats(r.board, from, r.board.nowMs - 1, r.board.busyCycles - cycles0);
      check(Math.abs(s.hz - 100) < 0.05 && s.worstDeviationUs < 100,
        `control tick ${s.hz.toFixed(2)} Hz of emulated time, ${s.ticks} ticks in ${s.seconds.toFixed(1)} s, worst period deviation ${s.worstDeviationUs.toFixed(0)} us`);
      console.log(`    --  CPU at rest: ${Math.round(s.cyclesPerTick)} cycles per 10 ms tick period (${s.busyPercent.toFixed(2)} % of 125 MHz; the whole loop: tick, USB, log port)`);
      benchRows.push({ name: `hil/${boardName}_idle`, inputs: { tick_hz: 100, mhz: 125 }, metrics: { cycles_per_tick: Math.round(s.cyclesPerTick), busy_percent: s.busyPercent, tick_hz: s.hz } });
    } finally {
      await r.close();
    }
  },

  /** rotctl -m 603 (GS-232B) go-to on the relay drive with the pot. */
  async 'goto-relay-pot-gs232'() {
    await gotoScenario({ profile: 'g5500', sensor: 'pot', model: 603, from: 100, to: 125, bench: 'relay_pot' });
  },
  /** rotctl -m 202 (Easycomm II) go-to on the H-bridge with the MA3 (PIO). */
  async 'goto-hbridge-ma3-easycomm'() {
    await gotoScenario({ profile: 'spid', sensor: 'ma3', model: 202, from: 100, to: 80, settings: { 'usb.personality': 'easycomm' }, bench: 'hbridge_ma3' });
  },
  /** The cross pairs: relay with the MA3, H-bridge with the pot. */
  async 'goto-relay-ma3-gs232'() {
    await gotoScenario({ profile: 'g5500', sensor: 'ma3', model: 603, from: 200, to: 215 });
  },
  async 'goto-hbridge-pot-easycomm'() {
    await gotoScenario({ profile: 'spid', sensor: 'pot', model: 202, from: 30, to: 50, settings: { 'usb.personality': 'easycomm' } });
  },

  /**
   * A two-speed G-5500 (az.drive relay_two_speed: the FAST relay on GPIO 7
   * selects the fast winding) with a 300 ms soft start and stop: it starts
   * slow, runs fast, and is slow again within az.slow_zone_deg (10) of the
   * target and for 300 ms or more before the direction relay breaks.
   */
  async 'goto-two-speed'() {
    await speedRelayScenario({ drive: 'relay_two_speed', settings: { 'az.soft_ms': 300 }, startMs: 300, stopMs: 300 });
  },
  /**
   * A voltage-select G-5500 with soft start and stop (az.drive
   * relay_voltage_select, az.soft_ms 500): the direction relay makes and
   * breaks on the creep supply only; the fast supply comes on 500 ms after
   * it and goes off at least az.soft_ms + az.dir_settle_ms (550) before it
   * breaks.
   */
  async 'goto-voltage-select-soft'() {
    await speedRelayScenario({ drive: 'relay_voltage_select', settings: { 'az.soft_ms': 500 }, startMs: 500, stopMs: 550 });
  },

  /**
   * A magnetometer for the azimuth (az.sensor mag: a QMC5883L at 0x0D on
   * I2C0, GPIO 0/1), calibrated for the mast's hard-iron field (the
   * simulator's x = 300 + 1200 cos, y = -150 + 900 sin): the firmware starts
   * the chip (SET/RESET period, continuous 50 Hz), reads its heading through
   * the I2C block, and a go-to reaches its target without hunting.
   */
  async 'goto-mag'() {
    const cal = { 'az.sensor': 'mag', 'mag.x_min': -900, 'mag.x_max': 1500, 'mag.y_min': -1050, 'mag.y_max': 750 };
    const r = await rig({ thetaDeg: 100, mag: true, noise: true, settings: cal });
    try {
      // Waited for, not looked up: USB enumerates about when the boot's
      // first log lines go out, and which comes first moves by microseconds
      // with the image's layout (a 1.3 KB larger .bss once lost this race,
      // read then as a firmware that stopped at boot).
      const found = await r.board.waitForLog(/magnetometer/, 1000);
      check(/QMC5883L at 0x0D/.test(found?.text ?? ''), `log: "${found?.text}"`);
      const wrote = (reg, value) => r.board.i2cLog.some((w) => w.register === reg && w.value === value);
      check(wrote(0x0b, 0x01) && wrote(0x09, 0x15), `the chip started: ${r.board.i2cLog.map((w) => `0x${w.register.toString(16)}=0x${w.value.toString(16)}`).join(', ')} (SET/RESET period, then continuous 50 Hz, 8 G, 512x)`);
      const p0 = (await rotctl(r, 603, 'p')).trim().split('\n').map(Number);
      check(Math.abs(p0[0] - 100) < 1, `rotctl -m 603 p: ${p0[0]} (plant 100)`);
      r.board.resetMotion();
      await rotctl(r, 603, 'P', '160', '0');
      check(await r.board.runUntil(() => driving(r), 3000, 1), 'the drive starts');
      const reached = await r.board.runUntil(() => Math.abs(angle(r) - 160) < 1.5 && !driving(r), 20000, 1);
      check(reached && (await settle(r, 5000)), `reached ${angle(r).toFixed(2)} deg for a target of 160`);
      const p = (await rotctl(r, 603, 'p')).trim().split('\n').map(Number);
      check(Math.abs(p[0] - angle(r)) < 1, `rotctl -m 603 p: ${p[0]} (plant ${angle(r).toFixed(2)})`);
      await checkNoHunting(r, { az: true });
    } finally {
      await r.close();
    }
  },

  /** az.sensor mag with no chip answering on the bus: the azimuth latches a sensor fault and never drives. */
  async 'mag-absent'() {
    const r = await rig({ thetaDeg: 100, settings: { 'az.sensor': 'mag', 'usb.personality': 'seed' } });
    const c = new LineClient(r);
    try {
      await r.board.run(1000);
      const q = await c.send('$Q');
      check(/,SENSOR_LOST$|,NO_SENSOR$/.test(q ?? ''), `$Q with no magnetometer: ${q}`);
      await c.send('$E');
      const refused = await c.send('$R,cw');
      await r.board.run(500);
      check(refused === '$ERR,FAULT' && !driving(r), `$R,cw refused: ${refused}; no drive`);
      const line = r.board.logLines.find((l) => /magnetometer/.test(l.text));
      check(/no QMC5883L answers at 0x0D on GPIO 0 SDA, 1 SCL/.test(line?.text ?? ''), `log: "${line?.text}"`);
    } finally {
      c.close();
      await r.close();
    }
  },

  /** Az/el: a G-5500 (relays and pots on both axes) with rotctl -m 603 (GS-232B W az el), noise on. */
  async 'goto-azel-relay-pot-gs232'() {
    await azelScenario({ profile: 'g5500', sensor: 'pot', model: 603, from: [100, 10], to: [130, 40] });
  },
  /** Az/el: a SPID (H-bridges and MA3s on both axes) with rotctl -m 202 (Easycomm AZ EL), noise on. */
  async 'goto-azel-hbridge-ma3-easycomm'() {
    await azelScenario({ profile: 'spid', sensor: 'ma3', model: 202, from: [100, 20], to: [80, 45], settings: { 'usb.personality': 'easycomm' } });
  },

  /**
   * A 450 deg G-5500 with a single-turn MA3 that powers up in the overlap at
   * 400 deg: the encoder reads 40, the overlap switch T1 (GPIO 9) is closed,
   * so the firmware takes the second turn. rotctl -m 603 (GS-232B, 450 deg
   * scale) reads 400, and P 420 turns 20 deg on into the overlap (had it
   * taken 40, that would be 380 deg the other way).
   */
  async 'overlap-power-up'() {
    const r = await rig({ sensor: 'ma3', thetaDeg: 400 });
    try {
      check(!r.board.rp.gpio[pins.az_t1].inputValue, `T1 (GPIO ${pins.az_t1}) reads low: closed above 360 deg`);
      const p0 = (await rotctl(r, 603, 'p')).trim().split('\n').map(Number);
      check(Math.abs(p0[0] - 400) < 0.6, `rotctl -m 603 p at power-up: ${p0[0]} (plant 400, the MA3 reads 40)`);
      let lowest = angle(r);
      r.board.resetMotion();
      await rotctl(r, 603, 'P', '420', '0');
      const there = () => {
        lowest = Math.min(lowest, angle(r));
        return Math.abs(angle(r) - 420) < 1.5 && !driving(r) && r.board.motion.az.starts > 0;
      };
      check((await r.board.runUntil(there, 15000, 1)) && (await settle(r, 5000)),
        `reached ${angle(r).toFixed(2)} deg for 420, never below ${lowest.toFixed(2)} deg`);
      check(r.board.motion.az.starts === 1 && r.board.motion.az.reversals === 0 && lowest > 399.5, 'one start, clockwise only');
      const p = (await rotctl(r, 603, 'p')).trim().split('\n').map(Number);
      check(Math.abs(p[0] - angle(r)) < 0.6, `rotctl -m 603 p: ${p[0]} (plant ${angle(r).toFixed(2)})`);
    } finally {
      await r.close();
    }
  },

  /** The seed protocol as a jog panel: enable, run CW, stop when the target is passed. */
  async 'seed-jog'() {
    const r = await rig({ thetaDeg: 100, settings: { 'usb.personality': 'seed' } });
    const c = new LineClient(r);
    try {
      check((await c.send('$E')) === '$OK,E', '$E enables');
      check((await c.send('$S,100')) === '$OK,S,100', '$S,100');
      check((await c.send('$R,cw')) === '$OK,R,CW', '$R,cw');
      let q = '';
      await r.board.runUntil(() => angle(r) >= 110, 6000, 10);
      q = await c.send('$Q');
      const az = Number(q.split(',')[1]);
      check(Math.abs(az - angle(r)) < 0.6, `$Q while turning: ${q} (plant ${angle(r).toFixed(2)})`);
      check((await c.send('$D')) === '$OK,D', '$D stops');
      check(await settle(r, 3000), 'the drive is off');
      check(angle(r) > 110 && angle(r) < 113, `stopped at ${angle(r).toFixed(2)} deg (passed 110 when $D was sent)`);
    } finally {
      c.close();
      await r.close();
    }
  },

  /** A limit switch that closes while turning cuts that direction on the first tick after. */
  async 'limit-switch'() {
    const r = await rig({ thetaDeg: 200 });
    const c = new LineClient(r);
    try {
      check((await c.send('R')) !== null, 'R (turn CW)');
      await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1);
      await r.board.run(300);
      check(r.board.outputLevel(pins.az_cw), `CW relay (GPIO ${pins.az_cw}) on`);
      await r.plant.command('limit cw 1 -1');
      await r.board.run(1); // the plant applies it at its next millisecond
      const closedMs = r.board.nowMs;
      check(!r.board.rp.gpio[pins.az_l2].inputValue, `L2 (GPIO ${pins.az_l2}) reads low: closed`);
      await r.board.runUntil(() => !r.board.outputLevel(pins.az_cw), 100, 0.1);
      const cut = r.board.edges.find((e) => e.gpio === pins.az_cw && !e.value && e.ms >= closedMs - 1);
      const tick = tickTimes(r.board, closedMs - 1, closedMs + 20).find((t) => t >= closedMs - 1);
      check(cut && tick !== undefined && cut.ms - closedMs <= TICK_MS + 0.5 && cut.ms - tick < 1,
        `CW cut ${(cut.ms - closedMs).toFixed(2)} ms after the switch closed, in the first tick after it (at +${(tick - closedMs).toFixed(2)} ms)`);
      const again = await c.send('R');
      check(again === '?>', `R refused while the CW limit is closed: "${again}"`);
      await r.board.run(200);
      check(!r.board.outputLevel(pins.az_cw), 'CW stays off');
    } finally {
      c.close();
      await r.close();
    }
  },

  /** The elevation's UP end switch (GPIO 19) closing while it turns up cuts UP on the first tick after it. */
  async 'el-limit-switch'() {
    await elLimitScenario({ command: 'U', relay: 'el_up', endSwitch: 'el_limit_up', plantSide: 'cw', fromDeg: 30 });
  },
  /** The DOWN end switch (GPIO 22) likewise, turning down. */
  async 'el-down-limit-switch'() {
    await elLimitScenario({ command: 'D', relay: 'el_down', endSwitch: 'el_limit_down', plantSide: 'ccw', fromDeg: 60 });
  },

  /** Push buttons (wired by settings: GPIO 4 and 13, free by default): held, the axis turns; released, it stops. */
  async 'buttons'() {
    const wired = { ...pins, btn_cw: 4, btn_ccw: 13 };
    const r = await rig({ thetaDeg: 200, pinMap: wired, settings: { 'buttons.enabled': 'true', 'pins.btn_cw': 4, 'pins.btn_ccw': 13 } });
    try {
      await r.board.run(300);
      check(!driving(r), 'released: no drive');
      r.board.press('btn_ccw', true);
      check(await r.board.runUntil(() => r.board.outputLevel(pins.az_ccw), 500, 1), `CCW button held: CCW relay (GPIO ${pins.az_ccw}) on`);
      await r.board.run(1000);
      const held = angle(r);
      check(held < 199.5, `the axis turned CCW to ${held.toFixed(2)} deg`);
      r.board.press('btn_ccw', false);
      const releasedMs = r.board.nowMs;
      check(await r.board.runUntil(() => !r.board.outputLevel(pins.az_ccw), 500, 1), `released: CCW off ${(r.board.nowMs - releasedMs).toFixed(1)} ms later (debounce ${30} ms)`);
      check(!r.board.outputLevel(pins.az_cw), 'CW never on');
    } finally {
      await r.close();
    }
  },

  /**
   * A Ham IV (ham4: relays, brake solenoid, pot): the brake relay releases
   * az.brake_release_ms (500) before the motor runs and engages
   * az.brake_engage_ms (3000) after it stops, while the antenna coasts;
   * braked, the axis holds where it stopped.
   */
  async 'brake-sequence'() {
    const r = await rig({ profile: 'ham4', sensor: 'pot', thetaDeg: 100 });
    const edge = (gpio, value, afterMs) => r.board.edges.find((e) => e.gpio === gpio && e.value === value && e.ms >= afterMs);
    try {
      await r.board.run(200);
      check(!r.board.outputLevel(pins.az_brake), `at rest the brake holds: its relay (GPIO ${pins.az_brake}) is off`);
      const sentMs = r.board.nowMs;
      await rotctl(r, 603, 'P', '130', '0');
      check(await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 3000, 1), 'the CW relay comes on');
      const released = edge(pins.az_brake, true, sentMs);
      const cwOn = edge(pins.az_cw, true, sentMs);
      // Edges carry the instant of the GPIO write within its tick (sub-ms jitter).
      check(released && cwOn.ms - released.ms >= 500 - 1 && cwOn.ms - released.ms <= 500 + TICK_MS + 0.5,
        `brake released ${(cwOn.ms - released?.ms).toFixed(1)} ms before the motor (az.brake_release_ms 500)`);
      check(await r.board.runUntil(() => !r.board.outputLevel(pins.az_cw), 15000, 1), 'the CW relay goes off');
      const cwOff = edge(pins.az_cw, false, cwOn.ms);
      check(r.board.outputLevel(pins.az_brake), 'the brake stays released while the antenna coasts');
      check(await r.board.runUntil(() => !r.board.outputLevel(pins.az_brake), 5000, 1), 'the brake engages');
      const engaged = edge(pins.az_brake, false, cwOff.ms);
      check(engaged.ms - cwOff.ms >= 3000 - 1 && engaged.ms - cwOff.ms <= 3000 + TICK_MS + 0.5,
        `brake engaged ${(engaged.ms - cwOff.ms).toFixed(1)} ms after the motor stopped (az.brake_engage_ms 3000)`);
      const heldDeg = angle(r);
      await r.board.run(2000);
      check(Math.abs(heldDeg - 130) < 1.5 && Math.abs(angle(r) - heldDeg) < 0.05 && !r.board.outputLevel(pins.az_brake),
        `braked at ${heldDeg.toFixed(2)} deg for a target of 130; 2 s later ${angle(r).toFixed(2)} deg`);
      const p = (await rotctl(r, 603, 'p')).trim().split('\n').map(Number);
      check(Math.abs(p[0] - angle(r)) < 0.6, `rotctl -m 603 p: ${p[0]} (plant ${angle(r).toFixed(2)})`);
    } finally {
      await r.close();
    }
  },

  /**
   * Soft reversal: CCW asked for while turning CW drops CW at once and
   * energises CCW only after az.reverse_dead_ms (1000) at standstill, never
   * both relays together.
   */
  async 'reversal-dead-time'() {
    const r = await rig({ thetaDeg: 200 });
    const c = new LineClient(r);
    try {
      check((await c.send('R')) !== null, 'R (turn CW)');
      check(await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1), 'CW relay on');
      await r.board.run(1000);
      const askedMs = r.board.nowMs;
      check((await c.send('L')) !== null, 'L (turn CCW) while turning CW');
      // When the antenna last turned faster than 0.1 deg/s (over 100 ms of
      // the plant's angle: its coast decays exponentially, never to exactly
      // zero, and the plant reports 0.0001 deg steps).
      const history = [{ ms: r.board.nowMs, deg: angle(r) }];
      let lastMovedMs = r.board.nowMs;
      const ccwOnNow = () => {
        history.push({ ms: r.board.nowMs, deg: angle(r) });
        while (history.length > 1 && history[1].ms <= r.board.nowMs - 100) history.shift();
        if (history[0].ms <= r.board.nowMs - 100 && Math.abs(angle(r) - history[0].deg) > 0.01) lastMovedMs = r.board.nowMs;
        return r.board.outputLevel(pins.az_ccw);
      };
      check(await r.board.runUntil(ccwOnNow, 6000, 1), 'CCW relay on');
      const cwOff = r.board.edges.find((e) => e.gpio === pins.az_cw && !e.value && e.ms >= askedMs);
      const ccwOn = r.board.edges.find((e) => e.gpio === pins.az_ccw && e.value && e.ms >= askedMs);
      check(cwOff && cwOff.ms - askedMs <= TICK_MS + 0.5, `CW dropped ${(cwOff?.ms - askedMs).toFixed(1)} ms after L reached the chip`);
      // The dead time counts from the end of the coast (the stop is judged
      // at rest: 4 x the learnt coast + 0.2 s, at most 3 s).
      const stillMs = ccwOn.ms - lastMovedMs;
      check(stillMs >= 1000 - 1 && ccwOn.ms - cwOff.ms <= 3000 + 1000 + 2 * TICK_MS,
        `CCW on ${(ccwOn.ms - cwOff.ms).toFixed(1)} ms after CW off, the antenna at rest for the last ${stillMs.toFixed(1)} ms of it (az.reverse_dead_ms 1000)`);
      check(!r.board.edges.some((e) => e.gpio === pins.az_ccw && e.value && e.ms < cwOff.ms && e.ms >= askedMs), 'never CW and CCW together');
      await c.send('S');
      check(await settle(r, 3000), 'S stops');
    } finally {
      c.close();
      await r.close();
    }
  },

  /** A jammed rotator: the stall rule cuts the drive after az.stall_ms and latches the fault. */
  async 'stall'() {
    const r = await rig({ thetaDeg: 200, settings: { 'usb.personality': 'seed' } });
    const c = new LineClient(r);
    try {
      await r.plant.command('jam -1'); // seized: the motor gets power, nothing turns
      await c.send('$E');
      await c.send('$R,cw');
      await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1);
      const on = r.board.edges.find((e) => e.gpio === pins.az_cw && e.value);
      await r.board.runUntil(() => !r.board.outputLevel(pins.az_cw), 5000, 1);
      const cut = r.board.edges.find((e) => e.gpio === pins.az_cw && !e.value && e.ms > on.ms);
      check(cut !== undefined, 'the CW relay was cut');
      const after = cut.ms - on.ms;
      check(Math.abs(after - 3000) <= TICK_MS + 0.5, `cut ${after.toFixed(1)} ms after it was energised (az.stall_ms 3000)`);
      const q = await c.send('$Q');
      check(q.endsWith(',STALL'), `fault latched: ${q}`);
      const refused = await c.send('$R,cw');
      check(refused === '$ERR,FAULT', `$R,cw refused: ${refused}`);
      await r.board.run(500);
      check(!r.board.outputLevel(pins.az_cw), 'CW stays off');
    } finally {
      c.close();
      await r.close();
    }
  },

  /**
   * The position sensor fails while turning, on the pins: an open pot wiper
   * (0 counts) or an MA3 that stops pulsing. The drive is cut and a sensor
   * fault latched once the readings have been bad for the grace time
   * (250 ms; the MA3's decoder first waits out its 100 ms edge timeout), not
   * on a single bad reading; the drive stays off.
   */
  async 'sensor-loss-pot'() {
    await sensorLossScenario({ profile: 'g5500', sensor: 'pot', fault: 'SENSOR_RANGE', graceMs: 250 });
  },
  async 'sensor-loss-ma3'() {
    await sensorLossScenario({ profile: 'spid', sensor: 'ma3', fault: 'SENSOR_LOST', graceMs: 100 + 250 });
  },

  /**
   * A noise burst on the MA3 (60 deg rms, a loose connector, interference):
   * the robust filter turns away readings off the axis's measured motion
   * (docs/care.md), carries the position on at the measured speed, and five
   * in a row latch SENSOR_JUMP and cut the drive. The position held is off
   * the antenna by no more than the tolerance (az.tolerance_deg 1) plus the
   * coast after the cut.
   */
  async 'sensor-burst-ma3'() {
    const r = await rig({ profile: 'spid', sensor: 'ma3', thetaDeg: 200, settings: { 'usb.personality': 'seed' } });
    const c = new LineClient(r);
    try {
      const { afterMs, q } = await sensorFaultDuringAJog(r, c, { runMs: 500, fault: 'SENSOR_JUMP', plantCommand: 'sensor burst 60 -1', timeoutMs: 2000 });
      check(afterMs >= 5 * TICK_MS - 1, `cut ${afterMs.toFixed(0)} ms into the burst (not before five readings in a row were rejected)`);
      const az = Number(q?.split(',')[1]);
      check(Math.abs(az - angle(r)) < 1.5, `the position held: ${az}, ${Math.abs(az - angle(r)).toFixed(2)} deg off the plant's ${angle(r).toFixed(2)} (az.tolerance_deg 1, plus the coast)`);
    } finally {
      c.close();
      await r.close();
    }
  },

  /**
   * A pot whose reading freezes (a corroded wiper) while the motor turns the
   * antenna: the reading, seen changing at speed, repeats the very same value
   * from one tick on (a jam slows down and its noise goes on), so the axis
   * latches SENSOR_STUCK 600 ms after the freeze instead of waiting for the
   * stall rule (az.stall_ms 3000).
   */
  async 'sensor-stuck-pot'() {
    const r = await rig({ thetaDeg: 200, settings: { 'usb.personality': 'seed' } });
    const c = new LineClient(r);
    try {
      const { afterMs, faultDeg } = await sensorFaultDuringAJog(r, c, { runMs: 1500, fault: 'SENSOR_STUCK', plantCommand: 'sensor stuck -1', timeoutMs: 5000 });
      check(afterMs >= 600 - TICK_MS && afterMs <= 1000,
        `cut ${afterMs.toFixed(0)} ms after the pot froze (within 1 s; az.stall_ms is 3000), the antenna having turned ${(angle(r) - faultDeg).toFixed(1)} deg meanwhile`);
    } finally {
      c.close();
      await r.close();
    }
  },

  /**
   * Wind stow from a cup anemometer on the emulated chip (docs/care.md, "Wind
   * stow"): wired on GPIO 13 (pins.wind, wind.source pulses: stored, as a
   * user's wiring is, since the counter is set up at boot), the rest set over
   * the console (wind.hold_s 2, wind.stow_az_deg 180). The harness closes the
   * reed contact 37.5 times a second (25 m/s at wind.pulses_per_mps 1.5,
   * above wind.stow_mps 20): the GPIO interrupt counts them, the antenna
   * turns from 200 to 180, and a GS-232 go-to is then refused.
   */
  async 'wind-pulses'() {
    const windPin = 13;
    const holdS = 2;
    const stowDeg = 180;
    const r = await rig({ thetaDeg: 200, settings: { 'wind.source': 'pulses', 'pins.wind': windPin } });
    const logBridge = new PtyBridge({ endpoint: r.board.logEndpoint() });
    const con = new LineClient({ board: r.board, pty: await logBridge.start() }, logBridge);
    const gs = new LineClient(r);
    try {
      r.board.anemometer(windPin, 0); // the contact open: the line pulled up
      const fitted = await r.board.waitForLog(/anemometer on GPIO/, 1000);
      check(fitted?.text.includes(`anemometer on GPIO ${windPin} (1.50 pulses per m/s)`), `log: "${fitted?.text}"`);
      for (const [key, value] of [['wind.hold_s', holdS], ['wind.stow_az_deg', stowDeg]]) {
        const set = await con.command(`set ${key} ${value}`);
        check(set.at(-1)?.startsWith(`ok ${key}=`), `console: set ${key} ${value}: "${set.at(-1)}"`);
      }
      await r.board.run(2500); // calm readings fill the meter's 2 s window
      const calm = (await con.command('wind')).find((l) => l.startsWith('wind source='));
      check(/source=pulses state=calm/.test(calm ?? ''), `console: "${calm}"`);
      check(!driving(r), 'no drive');
      const since = r.board.logLines.length;
      const windMs = r.board.nowMs;
      r.board.anemometer(windPin, 25 * 1.5);
      check(await r.board.runUntil(() => driving(r), holdS * 1000 + 5000, 1), 'the drive starts');
      const stowBeganMs = r.board.nowMs - (windMs + holdS * 1000);
      const line = await r.board.waitForLog(/wind: .* held for wind.hold_s: stowing/, 500, since);
      check(line !== null, `log: "${line?.text}"`);
      check(r.board.outputLevel(pins.az_ccw) && stowBeganMs > 0 && stowBeganMs <= 2000,
        `stow began ${stowBeganMs.toFixed(0)} ms after the wind had held for wind.hold_s (${holdS} s; goal within 2 s), turning CCW (${r.board.anemometerPulses} pulses played)`);
      const reached = await r.board.runUntil(() => Math.abs(angle(r) - stowDeg) < 1.5 && !driving(r), 15000, 1);
      check(reached && (await settle(r, 5000)), `stowed at ${angle(r).toFixed(2)} deg for wind.stow_az_deg ${stowDeg}, ${((r.board.nowMs - windMs) / 1000).toFixed(1)} s after the wind rose`);
      const status = (await con.command('wind')).filter((l) => l.startsWith('wind '));
      const speed = Number(status[0]?.match(/speed_mps=([\d.]+)/)?.[1]);
      check(/state=stowed/.test(status[0] ?? '') && /stows=1/.test(status[1] ?? '') && Math.abs(speed - 25) < 1.5,
        `console: "${status[0]}" / "${status[1]}"`);
      const refused = await gs.send('M250');
      await r.board.run(500);
      check(refused === '?>' && !driving(r), `GS-232 M250 refused while stowed: "${refused}", nothing moves`);
      const override = (await con.command('wind override 5')).find((l) => l.startsWith('wind source='));
      check(/state=override/.test(override ?? ''), `console: wind override 5: "${override}"`);
      check((await gs.send('M250')) !== '?>' && (await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1)),
        'overridden by the operator: M250 obeyed, CW on');
      await gs.send('S');
      check(await settle(r, 3000), 'S stops');
      // The wind drops to 5 m/s: the meter follows it down, and the calm
      // time (wind.calm_min, at least a minute; played in virtual time by
      // scenario_tests' Wind.*) starts counting.
      r.board.anemometer(windPin, 5 * 1.5);
      await r.board.run(2500);
      const easing = (await con.command('wind')).filter((l) => l.startsWith('wind '));
      const eased = Number(easing[0]?.match(/speed_mps=([\d.]+)/)?.[1]);
      const calmLeftS = Number(easing[1]?.match(/calm_left_s=(\d+)/)?.[1]);
      check(Math.abs(eased - 5) < 0.8 && calmLeftS < 600, `5 m/s played: console: "${easing[0]}" / "${easing[1]}"`);
      benchRows.push({ name: `hil/${boardName}_wind_stow`, inputs: { wind_mps: 25, pulses_per_mps: 1.5, hold_s: holdS }, metrics: { stow_began_ms_after_hold: Math.round(stowBeganMs) } });
    } finally {
      r.board.anemometer(windPin, 0);
      con.close();
      gs.close();
      await logBridge.stop();
      await r.close();
    }
  },

  /**
   * A slip on the emulated chip (docs/care.md, "Slip and uncommanded
   * motion"): a Ham IV at rest, its brake set and every output off; the
   * plant's wind turns the mast 3 deg in 0.75 s against the brake. The
   * firmware logs the slip (slip.deg 2) and switches nothing on. Then, with
   * slip.fault set over the console, a second gust latches SLIP and a
   * go-to is refused.
   */
  async 'slip'() {
    const r = await rig({ profile: 'ham4', sensor: 'pot', thetaDeg: 100 });
    const logBridge = new PtyBridge({ endpoint: r.board.logEndpoint() });
    const con = new LineClient({ board: r.board, pty: await logBridge.start() }, logBridge);
    const gs = new LineClient(r);
    const outputsOn = (fromMs) => r.board.edges.filter((e) => e.value && e.ms >= fromMs);
    try {
      await r.board.run(1500); // at rest since boot
      check(!driving(r) && !r.board.outputLevel(pins.az_brake), 'at rest, the outputs off, the brake set');
      let since = r.board.logLines.length;
      const gustMs = r.board.nowMs;
      await r.plant.command('slip 4 0.75'); // 3 deg in 0.75 s
      const line = await r.board.waitForLog(/az: slip:/, 2000, since);
      const flaggedMs = (line?.ms ?? NaN) - gustMs;
      check(line !== null && /now at 10[0-9]\.\d deg \(1 slips since start\)/.test(line.text), `log: "${line?.text}"`);
      check(flaggedMs <= 1000, `slip flagged ${flaggedMs.toFixed(0)} ms after the mast began to turn (2 deg at 4 deg/s: 500 ms; goal within 1 s)`);
      await r.board.run(1500);
      check(outputsOn(gustMs).length === 0 && !driving(r), `no output switched on (plant at ${angle(r).toFixed(2)} deg)`);
      const set = await con.command('set slip.fault true');
      check(/^ok slip.fault=/.test(set.at(-1) ?? ''), `console: set slip.fault true: "${set.at(-1)}"`);
      since = r.board.logLines.length;
      const secondMs = r.board.nowMs;
      await r.plant.command('slip -4 0.75');
      check((await r.board.waitForLog(/az: slip:.*\(2 slips since start\)/, 2000, since)) !== null, 'a second gust: a second slip');
      const az = (await con.command('status')).find((l) => l.startsWith('az '));
      check(/fault=SLIP/.test(az ?? ''), `console status: "${az}"`);
      const refused = await gs.send('M150');
      await r.board.run(500);
      check(refused === '?>' && outputsOn(secondMs).length === 0, `GS-232 M150 refused with SLIP latched: "${refused}", no output switched on`);
      benchRows.push({ name: `hil/${boardName}_slip`, inputs: { slip_deg: 3, slip_deg_s: 4 }, metrics: { flagged_ms: Math.round(flaggedMs) } });
    } finally {
      con.close();
      gs.close();
      await logBridge.stop();
      await r.close();
    }
  },

  /** A hung loop: the watchdog resets the chip within 2 s; the relay drops and the firmware comes back. */
  async 'watchdog'() {
    const r = await rig({ thetaDeg: 200 });
    const c = new LineClient(r);
    try {
      await c.send('R');
      await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1);
      await r.board.run(200);
      // The harness stops the core from the outside: no instruction runs,
      // the timers and the watchdog go on (a loop stuck in a busy wait
      // would look the same from the pins).
      r.board.hang();
      const hungMs = r.board.nowMs;
      await r.board.run(1000);
      check(r.board.outputLevel(pins.az_cw), 'hung: the CW relay is still on (nothing else turns it off)');
      await r.board.runUntil(() => r.board.resets > 0, 2000, 1);
      const resetMs = r.board.baseNs / 1e6;
      check(r.board.resets === 1 && Math.abs(resetMs - hungMs - 2000) < 15, `watchdog reset ${(resetMs - hungMs).toFixed(1)} ms after the loop stopped (2000 ms)`);
      check(!r.board.outputLevel(pins.az_cw), 'the reset dropped the CW relay');
      const line = await r.board.waitForLog(/restarted by the watchdog \(the loop hung\)/, 3000);
      check(line !== null, `log: "${line?.text}"`);
      const p = await c.send('C2', 3000);
      check(/^AZ=\d{3}/.test(p ?? ''), `GS-232 answers again: ${p}`);
    } finally {
      c.close();
      await r.close();
    }
  },

  /**
   * The console on the log port, through a second pty: status shows a
   * latched stall, reset clears it (GS-232 has no command for that), set
   * changes a setting, reboot restarts the chip.
   */
  async 'console'() {
    const r = await rig({ thetaDeg: 200 });
    const logBridge = new PtyBridge({ endpoint: r.board.logEndpoint() });
    const con = new LineClient({ board: r.board, pty: await logBridge.start() }, logBridge);
    const gs = new LineClient(r);
    try {
      await r.plant.command('jam -1');
      await gs.send('R');
      await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1);
      await r.board.runUntil(() => !r.board.outputLevel(pins.az_cw), 4000, 5);
      let status = await con.command('status');
      const az = status.find((l) => l.startsWith('az '));
      check(/fault=STALL/.test(az ?? ''), `status after the stall: "${az}"`);
      check((await gs.send('R')) === '?>', 'GS-232 R refused while the fault is latched');
      await r.plant.command('clear');
      const reset = await con.command('reset');
      check(reset.at(-1) === 'ok stopped, faults cleared', `reset: "${reset.at(-1)}"`);
      status = await con.command('status');
      check(/fault=NONE|fault=-|fault=none/i.test(status.find((l) => l.startsWith('az ')) ?? ''), `status after reset: "${status.find((l) => l.startsWith('az '))}"`);
      await gs.send('R');
      check(await r.board.runUntil(() => r.board.outputLevel(pins.az_cw), 2000, 1), 'GS-232 R turns CW again');
      await gs.send('S');
      const set = await con.command('set az.stall_ms 1500');
      check(set.at(-1) === 'ok az.stall_ms=1500', `set: "${set.at(-1)}"`);
      const bad = await con.command('set az.stall_ms 5');
      check(bad.at(-1)?.startsWith('error: '), `a bad value is refused: "${bad.at(-1)}"`);
      const since = r.board.logLines.length;
      const reboot = await con.command('reboot');
      check(reboot.at(-1) === 'ok rebooting', `reboot: "${reboot.at(-1)}"`);
      const banner = await r.board.waitForLog(/^rotord \d/, 3000, since);
      check(banner !== null && r.board.boots === 2 && /reboot requested/.test(banner.text), `the chip restarted: "${banner?.text}"`);
      const stored = readSettings(r.board.flash);
      check(/"az.stall_ms": 1500/.test(stored?.document ?? ''), `az.stall_ms 1500 saved before the reboot (save #${stored?.sequence})`);
    } finally {
      con.close();
      gs.close();
      await logBridge.stop();
      await r.close();
    }
  },

  /** The console's bootsel: the chip reboots into the ROM's USB bootloader (mass storage + PICOBOOT). */
  async 'bootsel'() {
    const r = await rig({ thetaDeg: 200 });
    const logBridge = new PtyBridge({ endpoint: r.board.logEndpoint() });
    const con = new LineClient({ board: r.board, pty: await logBridge.start() }, logBridge);
    try {
      check(r.board.usb.interfaceClasses.includes(2), `rotord enumerates CDC (interface classes ${r.board.usb.interfaceClasses})`);
      const reply = await con.command('bootsel');
      check(reply.at(-1)?.startsWith('ok rebooting into the USB bootloader'), `bootsel: "${reply.at(-1)}"`);
      check(await r.board.runUntil(() => r.board.boots === 2 && r.board.romEntry, 2000, 1), 'the chip reset into the bootrom');
      check(await r.board.runUntil(() => r.board.usb.interfaceClasses?.length > 0, 3000, 5), 'the bootloader enumerates');
      const classes = r.board.usb.interfaceClasses;
      check(classes.includes(8) && classes.includes(0xff) && !classes.includes(2), `as the RPI-RP2 drive and PICOBOOT (interface classes ${classes}: mass storage, vendor)`);
    } finally {
      con.close();
      await logBridge.stop();
      await r.close();
    }
  },

  /** A setting changed over USB is saved to flash and survives a power cycle. */
  async 'flash-settings'() {
    const r = await rig({ thetaDeg: 200 });
    const c = new LineClient(r);
    try {
      const reply = await c.send('P36');
      check(reply !== null && reply !== '?>', `P36 accepted: "${reply}"`);
      const saved = await r.board.waitForLog(/settings saved to flash/, 6000);
      check(saved !== null, `log: "${saved?.text}" (erases ${r.board.flashStats.erases}, page programs ${r.board.flashStats.programs})`);
      const stored = readSettings(r.board.flash);
      check(stored && /"gs232.az_range": "360"/.test(stored.document), `flash slot ${stored?.slot}, save #${stored?.sequence} holds gs232.az_range = 360`);
      const since = r.board.logLines.length;
      r.board.powerCycle();
      const loaded = await r.board.waitForLog(/settings loaded from flash/, 2000, since);
      check(loaded && loaded.text.includes(`save #${stored.sequence}`), `after a power cycle: "${loaded?.text}"`);
      await r.board.runUntil(() => r.board.usbConnectedMs !== undefined, 3000);
      const m = await c.send('M400');
      check(m === '?>', `M400 refused on the 360 scale kept from flash: "${m}"`);
    } finally {
      c.close();
      await r.close();
    }
  },
};

async function gotoScenario({ profile, sensor, model, from, to, settings = {}, bench }) {
  // The simulator's sensor noise on (seeded: every run sees the same noise).
  const r = await rig({ profile, sensor, thetaDeg: from, settings, noise: true });
  try {
    const p0 = (await rotctl(r, model, 'p')).trim().split('\n').map(Number);
    check(Math.abs(p0[0] - from) < 0.6, `rotctl -m ${model} p: ${p0[0]} (plant ${from})`);
    r.board.resetMotion();
    await rotctl(r, model, 'P', String(to), '0');
    // Timed from the drive's start: when rotctl's bytes reach the chip is a
    // matter of the wall clock.
    check(await r.board.runUntil(() => driving(r), 3000, 1), 'the drive starts');
    const cycles0 = r.board.busyCycles;
    const t0 = r.board.nowMs;
    const reached = await r.board.runUntil(() => Math.abs(angle(r) - to) < 1.5 && !driving(r), 15000, 1);
    const moveS = (r.board.nowMs - t0) / 1000;
    const moveCycles = r.board.busyCycles - cycles0;
    check(reached && (await settle(r, 5000)), `reached ${angle(r).toFixed(2)} deg for a target of ${to}, the drive on for ${moveS.toFixed(2)} s`);
    const p = (await rotctl(r, model, 'p')).trim().split('\n').map(Number);
    check(Math.abs(p[0] - angle(r)) < 0.6 && Math.abs(p[0] - to) < 1.5, `rotctl -m ${model} p: ${p[0]} (plant ${angle(r).toFixed(2)})`);
    await checkNoHunting(r, { az: true });
    if (bench) {
      const cyclesPerTick = Math.round(moveCycles / (moveS * 100));
      console.log(`    --  CPU while moving: ${cyclesPerTick} cycles per 10 ms tick period`);
      benchRows.push({ name: `hil/${boardName}_goto_${bench}`, inputs: { move_deg: Math.abs(to - from) }, metrics: { cycles_per_tick: cyclesPerTick } });
    }
  } finally {
    await r.close();
  }
}

/**
 * A go-to from 100 to 160 deg on a relay drive with a speed relay (GPIO 7):
 * the speed relay comes on `startMs` or more after the direction relay,
 * goes off `stopMs` or more before it, and goes off within the slow zone
 * (10 deg) of the target; the target is reached with one start, no hunting.
 */
async function speedRelayScenario({ drive, settings = {}, startMs, stopMs }) {
  const r = await rig({ profile: 'g5500', drive, sensor: 'pot', thetaDeg: 100, settings, noise: true });
  const to = 160;
  try {
    r.board.resetMotion();
    const sentMs = r.board.nowMs;
    await rotctl(r, 603, 'P', String(to), '0');
    // The plant's angle when the speed relay last dropped, and the fastest
    // speed seen with it on and with it off (over 500 ms, once the relay has
    // held for 1 s: the motor's speed has settled).
    let fastOffDeg = NaN;
    let wasFast = false;
    let switchedMs = r.board.nowMs;
    const history = [];
    const topDegS = { fast: 0, slow: 0 };
    const there = () => {
      const fast = r.board.outputLevel(pins.az_speed);
      if (wasFast && !fast) fastOffDeg = angle(r);
      if (fast !== wasFast) switchedMs = r.board.nowMs;
      wasFast = fast;
      history.push({ ms: r.board.nowMs, deg: angle(r) });
      while (history.length > 1 && history[1].ms <= r.board.nowMs - 500) history.shift();
      const h = history[0];
      if (h.ms <= r.board.nowMs - 500 && h.ms >= switchedMs + 1000 && driving(r)) {
        const degS = ((angle(r) - h.deg) * 1000) / (r.board.nowMs - h.ms);
        const k = fast ? 'fast' : 'slow';
        topDegS[k] = Math.max(topDegS[k], degS);
      }
      return Math.abs(angle(r) - to) < 1.5 && !driving(r) && r.board.nowMs - sentMs > 1000;
    };
    check(await r.board.runUntil(() => driving(r), 3000, 1), 'the drive starts');
    check((await r.board.runUntil(there, 30000, 1)) && (await settle(r, 5000)), `reached ${angle(r).toFixed(2)} deg for a target of ${to}`);
    const edges = r.board.edges.filter((e) => e.ms >= sentMs);
    const cwOn = edges.find((e) => e.gpio === pins.az_cw && e.value);
    const cwOff = edges.find((e) => e.gpio === pins.az_cw && !e.value);
    const speed = edges.filter((e) => e.gpio === pins.az_speed);
    const firstOn = speed.find((e) => e.value);
    const lastOff = speed.findLast((e) => !e.value);
    check(firstOn && lastOff && speed.every((e) => e.ms > cwOn.ms && e.ms < cwOff.ms),
      `the speed relay (GPIO ${pins.az_speed}) switched ${speed.length} times, each while CW held`);
    check(firstOn.ms - cwOn.ms >= startMs - 1,
      `fast ${(firstOn.ms - cwOn.ms).toFixed(1)} ms after CW made (${startMs} ms or more)`);
    check(cwOff.ms - lastOff.ms >= stopMs - 1,
      `fast off ${(cwOff.ms - lastOff.ms).toFixed(1)} ms before CW broke (${stopMs} ms or more)`);
    check(to - fastOffDeg > 0 && to - fastOffDeg <= 10 + 1,
      `slow from ${fastOffDeg.toFixed(2)} deg on, ${(to - fastOffDeg).toFixed(2)} deg before the target (az.slow_zone_deg 10)`);
    check(topDegS.fast > 5.5 && topDegS.slow < 3.2,
      `${topDegS.fast.toFixed(2)} deg/s at the most on the fast winding or supply, ${topDegS.slow.toFixed(2)} on the slow one (the plant: 6 and 3)`);
    await checkNoHunting(r, { az: true });
  } finally {
    await r.close();
  }
}

/**
 * An elevation end switch closing while GS-232 `command` (U or D) turns that
 * way: the relay is cut within a tick, the command is then refused, and the
 * azimuth never moves.
 */
async function elLimitScenario({ command, relay, endSwitch, plantSide, fromDeg }) {
  const r = await rig({ elSensor: 'pot', thetaDeg: 200, elThetaDeg: fromDeg });
  const c = new LineClient(r);
  const name = relay.slice(3).toUpperCase();
  try {
    check((await c.send(command)) !== null, `${command} (turn ${name.toLowerCase()})`);
    check(await r.board.runUntil(() => r.board.outputLevel(pins[relay]), 2000, 1), `${name} relay (GPIO ${pins[relay]}) on`);
    await r.board.run(300);
    await r.plant.command(`limit el ${plantSide} 1 -1`);
    await r.board.run(1); // the plant applies it at its next millisecond
    const closedMs = r.board.nowMs;
    check(!r.board.rp.gpio[pins[endSwitch]].inputValue, `the ${name} end switch (GPIO ${pins[endSwitch]}) reads low: closed`);
    await r.board.runUntil(() => !r.board.outputLevel(pins[relay]), 100, 0.1);
    const cut = r.board.edges.find((e) => e.gpio === pins[relay] && !e.value && e.ms >= closedMs - 1);
    check(cut && cut.ms - closedMs <= TICK_MS + 0.5, `${name} cut ${(cut?.ms - closedMs).toFixed(2)} ms after the switch closed (within a tick)`);
    const again = await c.send(command);
    await r.board.run(200);
    check(again === '?>' && !r.board.outputLevel(pins[relay]), `${command} refused while the ${name} end switch is closed: "${again}", ${name} stays off`);
    check(!r.board.outputLevel(pins.az_cw) && !r.board.outputLevel(pins.az_ccw), 'the azimuth never moved');
  } finally {
    c.close();
    await r.close();
  }
}

/**
 * A CW jog on the seed protocol, `runMs` under way when the plant's
 * `sensor ...` fault is injected: checks that the drive is then cut and the
 * fault latched; returns how long after the fault the cut came, the plant's
 * angle at the fault and the $Q reply.
 */
async function sensorFaultDuringAJog(r, c, { runMs, fault, plantCommand, timeoutMs }) {
  await c.send('$E');
  check((await c.send('$R,cw')) === '$OK,R,CW', '$R,cw');
  check(await r.board.runUntil(() => driving(r), 2000, 1), 'the drive is on');
  await r.board.run(runMs);
  await r.plant.command(plantCommand);
  await r.board.run(1); // the plant applies it at its next millisecond
  const faultMs = r.board.nowMs;
  const faultDeg = angle(r);
  check(await r.board.runUntil(() => !driving(r), timeoutMs, 1), 'the drive is cut');
  const afterMs = r.board.nowMs - faultMs;
  const q = await c.send('$Q');
  check(q?.endsWith(`,${fault}`), `fault latched: ${q}`);
  return { afterMs, faultDeg, q };
}

/** The sensor lost under a jog: the cut, its delay, the fault latched and the drive refused. */
async function sensorLossScenario({ profile, sensor, fault, graceMs }) {
  const r = await rig({ profile, sensor, thetaDeg: 200, settings: { 'usb.personality': 'seed' } });
  const c = new LineClient(r);
  try {
    const { afterMs } = await sensorFaultDuringAJog(r, c, { runMs: 500, fault, plantCommand: 'sensor loss -1', timeoutMs: 2000 });
    check(afterMs >= graceMs - 1 && afterMs <= graceMs + 2 * TICK_MS + 5,
      `cut ${afterMs.toFixed(0)} ms after the ${sensor} was lost (grace ${graceMs} ms)`);
    const refused = await c.send('$R,cw');
    check(refused === '$ERR,FAULT', `$R,cw refused: ${refused}`);
    await r.board.run(500);
    check(!driving(r), 'the drive stays off');
  } finally {
    c.close();
    await r.close();
  }
}

/** A go-to on both axes: both targets reached and read back, on noisy sensors, without hunting. */
async function azelScenario({ profile, sensor, model, from, to, settings = {} }) {
  const r = await rig({ profile, sensor, elSensor: sensor, thetaDeg: from[0], elThetaDeg: from[1], settings, noise: true });
  try {
    const p0 = (await rotctl(r, model, 'p')).trim().split('\n').map(Number);
    check(Math.abs(p0[0] - from[0]) < 0.6 && Math.abs(p0[1] - from[1]) < 0.6, `rotctl -m ${model} p: ${p0[0]} ${p0[1]} (plant ${from[0]} ${from[1]})`);
    r.board.resetMotion();
    await rotctl(r, model, 'P', String(to[0]), String(to[1]));
    check(await r.board.runUntil(() => driving(r), 3000, 1), 'the drive starts');
    const t0 = r.board.nowMs;
    const there = () => Math.abs(angle(r) - to[0]) < 1.5 && Math.abs(elAngle(r) - to[1]) < 1.5 && !driving(r);
    const reached = await r.board.runUntil(there, 30000, 1);
    const moveS = (r.board.nowMs - t0) / 1000;
    check(reached && (await settle(r, 5000)) && there(),
      `reached az ${angle(r).toFixed(2)} el ${elAngle(r).toFixed(2)} deg for ${to[0]} ${to[1]} in ${moveS.toFixed(2)} s`);
    const p = (await rotctl(r, model, 'p')).trim().split('\n').map(Number);
    check(Math.abs(p[0] - angle(r)) < 0.6 && Math.abs(p[1] - elAngle(r)) < 0.6,
      `rotctl -m ${model} p: ${p[0]} ${p[1]} (plant ${angle(r).toFixed(2)} ${elAngle(r).toFixed(2)})`);
    await checkNoHunting(r, { az: true, el: true });
  } finally {
    await r.close();
  }
}

// ---- run ----

if (!existsSync(imagePath)) {
  console.error(`hil: no firmware image at ${imagePath} (make pico)`);
  process.exit(2);
}
console.log(`hil: ${boardName}: ${imagePath} on rp2040js, plant ${plantBinary}`);
// What malloc must still have after the most a scenario used: the network
// side, which the emulated chip never runs (no Wi-Fi chip), allocates too:
// mbedtls' HMAC context for a login (about 250 bytes) and the bigints of
// number parsing in JSON bodies (newlib's strtod, a few hundred).
const HEAP_SPARE_BYTES = 1024;

/**
 * What each chip of the scenario took of the heap, printed once: newlib's
 * malloc gets only the RAM between the static data and the stack
 * (ports/pico_w/README.md, RAM), so static RAM that grows into what the
 * firmware mallocs would stop it where a malloc first fails. Returns why
 * the heap is too tight, or null.
 */
function reportHeap(name) {
  let tight = null;
  for (const board of scenarioBoards.splice(0)) {
    const h = board.heap();
    if (!h) continue;
    console.log(`    heap: ${h.highWater} bytes used at most, ${h.sbrked} taken from sbrk, of ${h.room} between the static RAM and the stack`);
    heapRows.push({ scenario: name, ...h });
    if (h.room - h.highWater < HEAP_SPARE_BYTES)
      tight = `the heap: ${h.highWater} of ${h.room} bytes used, fewer than ${HEAP_SPARE_BYTES} to spare for the network's allocations`;
  }
  return tight;
}

let failed = 0;
for (const [name, fn] of Object.entries(scenarios)) {
  if (only.length && !only.includes(name)) continue;
  const wall0 = Date.now();
  console.log(`hil: ${name}`);
  scenarioBoards.length = 0;
  try {
    await fn();
    const tight = reportHeap(name);
    if (tight) throw new Error(tight);
    results.push({ name, ok: true });
    console.log(`PASS ${name} (${((Date.now() - wall0) / 1000).toFixed(1)} s wall)`);
  } catch (e) {
    failed++;
    reportHeap(name);
    results.push({ name, ok: false, error: e.message });
    console.log(`FAIL ${name}: ${e.message}`);
    if (verbose) console.log(e.stack);
  }
}
if (heapRows.length) {
  const used = Math.max(...heapRows.map((h) => h.highWater));
  benchRows.push({ name: `hil/${boardName}_heap`, inputs: { scenarios: results.length }, metrics: { heap_used_max_bytes: used, heap_room_bytes: Math.min(...heapRows.map((h) => h.room)) } });
}
if (benchRows.length) {
  mkdirSync(dirname(outPath), { recursive: true });
  writeFileSync(outPath, JSON.stringify(benchRows, null, 1) + '\n');
}
console.log(`hil: ${boardName}: ${results.length - failed} of ${results.length} scenarios passed`);
process.exit(failed ? 1 : 0);
