// The simulator's plant (sim/) in its own process, rotord_hil_plant
// (tests/hil/plant/hil_plant.cpp), one request line and one reply line at a
// time over its stdin/stdout.
import { spawn } from 'node:child_process';
import { createInterface } from 'node:readline';

/** A POT field: one code, or several conversions comma-separated (--pot-samples). */
function pot(field) {
  const potSamples = field.split(',').map(Number);
  return { potCounts: potSamples[0], potSamples };
}

export class Plant {
  /**
   * opts: { binary, profile, sensor, thetaDeg, speedScale, noise, drive,
   *         elSensor (plays the elevation too: 'pot' or 'ma3'), elThetaDeg,
   *         potSamples (conversions per pot per step, each with its own noise),
   *         mag (a QMC5883L on the azimuth: each step carries its registers) }
   */
  constructor(opts) {
    const args = ['--profile', opts.profile ?? 'g5500'];
    if (opts.sensor) args.push('--sensor', opts.sensor);
    if (opts.thetaDeg !== undefined) args.push('--theta', String(opts.thetaDeg));
    if (opts.speedScale !== undefined) args.push('--speed-scale', String(opts.speedScale));
    if (opts.noise) args.push('--noise', 'on');
    if (opts.elSensor) args.push('--el', opts.elSensor);
    if (opts.elThetaDeg !== undefined) args.push('--theta-el', String(opts.elThetaDeg));
    if (opts.potSamples !== undefined) args.push('--pot-samples', String(opts.potSamples));
    if (opts.drive) args.push('--drive', opts.drive);
    if (opts.mag) args.push('--mag', 'on');
    this.playsEl = Boolean(opts.elSensor);
    this.hasMag = Boolean(opts.mag);
    this.proc = spawn(opts.binary, args, { stdio: ['pipe', 'pipe', 'inherit'] });
    this.waiting = [];
    this.lines = createInterface({ input: this.proc.stdout });
    this.lines.on('line', (line) => {
      const w = this.waiting.shift();
      if (w) w(line);
    });
    this.proc.on('exit', () => {
      for (const w of this.waiting.splice(0)) w('error: the plant exited');
    });
  }

  request(line) {
    return new Promise((resolve) => {
      this.waiting.push(resolve);
      this.proc.stdin.write(line + '\n');
    });
  }

  /** A request answered by `n` lines. */
  requestLines(line, n) {
    const replies = [];
    for (let i = 0; i < n; i++) replies.push(new Promise((resolve) => this.waiting.push(resolve)));
    this.proc.stdin.write(line + '\n');
    return Promise.all(replies);
  }

  async command(line) {
    const reply = await this.request(line);
    if (reply !== 'ok') throw new Error(`plant: ${line}: ${reply}`);
  }

  /** Outputs held from now (the elevation's `uEl` when it plays one), then advance to ms; the sensors at ms. */
  async step(ms, u, uEl) {
    let line = `s ${ms} ${u.cw} ${u.ccw} ${u.fast} ${u.brake} ${u.pwmCw.toFixed(4)} ${u.pwmCcw.toFixed(4)}`;
    if (this.playsEl) {
      const e = uEl ?? { cw: 0, ccw: 0, fast: 0, pwmCw: 0, pwmCcw: 0 };
      line += ` ${e.cw} ${e.ccw} ${e.fast} ${e.pwmCw.toFixed(4)} ${e.pwmCcw.toFixed(4)}`;
    }
    const reply = await this.request(line);
    const f = reply.split(' ');
    // The magnetometer's registers 0x00..0x0D, last (with --mag).
    const mag = this.hasMag && f.at(-1).startsWith('MAG=') ? Buffer.from(f.pop().slice(4), 'hex') : undefined;
    if (f.length !== (this.playsEl ? 18 : 10) || (this.hasMag && mag?.length !== 14)) throw new Error(`plant: ${reply}`);
    const el = this.playsEl
      ? {
          thetaDeg: Number(f[10]),
          ...pot(f[11]),
          ma3Valid: f[12] === '1',
          ma3HighUs: Number(f[13]),
          ma3LowUs: Number(f[14]),
          limitCw: f[15] === '1', // UP
          limitCcw: f[16] === '1', // DOWN
          stalled: f[17] === '1',
        }
      : undefined;
    return {
      el,
      thetaDeg: Number(f[0]),
      ...pot(f[1]),
      ma3Valid: f[2] === '1',
      ma3HighUs: Number(f[3]),
      ma3LowUs: Number(f[4]),
      limitCw: f[5] === '1',
      limitCcw: f[6] === '1',
      t1: f[7] === '1',
      t2: f[8] === '1',
      stalled: f[9] === '1',
      magRegisters: mag,
    };
  }

  /** The stored settings document for this profile plus `extra` (KEY=VALUE). */
  async settingsDocument(extra = {}) {
    const pairs = Object.entries(extra).map(([k, v]) => `${k}=${v}`);
    const [doc, end] = await this.requestLines(`settings ${pairs.join(' ')}`, 2);
    if (doc.startsWith('error')) throw new Error(`plant: ${doc}`);
    if (end !== 'end') throw new Error(`plant: settings: ${end}`);
    return doc.trim();
  }

  close() {
    this.proc.stdin.end('q\n');
  }
}
