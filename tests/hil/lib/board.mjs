// A Pico or Pico W on an emulated RP2040 (rp2040js 1.4.1) with the rotator on its
// pins: the unmodified firmware image, the B1 bootrom (read from a path given
// at run time), the simulator's plant (lib/plant.mjs) stepped every emulated
// millisecond, and a USB host bound to both CDC ports. Everything runs on
// emulated time; the wall clock never enters a result.
//
// What the harness adds because rp2040js 1.4.1 does not model it
// (docs: /ports/pico_w/README.md, "The firmware on an emulated RP2040"):
// - PIO: stepped on emulated time at each state machine's clock divider
//   (rp2040js steps it from setTimeout, so the MA3 would always read 0);
// - pull-ups: the switch pins are driven by the harness (closed = low);
// - the log port: lib/usb_host.mjs binds every CDC port;
// - flash erase/program (lib/flash.mjs), and the reset a watchdog causes
//   (a new chip on the same flash, with the watchdog's reason and scratch
//   registers kept).
import { readFileSync } from 'node:fs';
import { RP2040, ConsoleLogger, LogLevel } from 'rp2040js';
import { elfSymbols } from './elf.mjs';
import { installFlashModel, writeSettingsSlot } from './flash.mjs';
import { adcChannel, driveDirection, elPlantInputs, ma3Frame, plantInputs, pwmDuty, switchLevels } from './pins.mjs';
import { UsbHost } from './usb_host.mjs';

const NS_PER_CYCLE = 8; // 125 MHz
const PIO_CATCH_UP_NS = 50_000; // the PIO never lags the CPU by more than this

/** The B1 bootrom: the rp2040js repository's demo/bootrom.ts, or a raw 16 KB image. */
export function loadBootrom(path) {
  if (!path) throw new Error('no bootrom: set ROTORD_RP2040_BOOTROM');
  const data = readFileSync(path);
  if (path.endsWith('.ts') || path.endsWith('.js')) {
    const words = data.toString('utf8').split('Uint32Array([')[1]?.match(/0x[0-9a-fA-F]+/g) ?? [];
    if (words.length !== 4096) throw new Error(`${path}: expected 4096 bootrom words, found ${words.length}`);
    return Uint32Array.from(words, (w) => Number(w));
  }
  if (data.length !== 16384) throw new Error(`${path}: a bootrom image is 16384 bytes`);
  return new Uint32Array(data.buffer, data.byteOffset, 4096);
}

/** The flash contents of a firmware image (.elf: its PT_LOAD segments in XIP flash; .bin: as is). */
export function loadImage(path, flash) {
  const data = readFileSync(path);
  if (data.readUInt32BE(0) !== 0x7f454c46) {
    flash.set(data, 0);
    return;
  }
  const phoff = data.readUInt32LE(28);
  const phentsize = data.readUInt16LE(42);
  const phnum = data.readUInt16LE(44);
  for (let i = 0; i < phnum; i++) {
    const ph = phoff + i * phentsize;
    const type = data.readUInt32LE(ph);
    const offset = data.readUInt32LE(ph + 4);
    const paddr = data.readUInt32LE(ph + 12);
    const filesz = data.readUInt32LE(ph + 16);
    if (type !== 1 || filesz === 0) continue;
    if (paddr < 0x10000000 || paddr >= 0x10000000 + flash.length) continue; // RAM-only (.bss)
    flash.set(data.subarray(offset, offset + filesz), paddr - 0x10000000);
  }
}

export class Board {
  /**
   * opts: { bootrom (Uint32Array), image (path), pins (lib/pins.mjs pinDefaults),
   *         plant (lib/plant.mjs Plant), flash (optional Uint8Array to start from),
   *         echoLog (print the log port) }
   */
  constructor(opts) {
    this.opts = opts;
    this.pins = opts.pins;
    this.plant = opts.plant;
    this.flash = opts.flash ?? new Uint8Array(16 * 1024 * 1024).fill(0xff);
    if (!opts.flash) loadImage(opts.image, this.flash);
    // Settings preloaded as the firmware would have saved them (slot 0, save #1).
    if (opts.settingsDocument) writeSettingsSlot(this.flash, opts.settingsDocument);
    this.baseNs = 0; // emulated time before the last reset
    this.log = '';
    this.logLines = []; // { ms, text }
    this.partialLine = '';
    this.edges = []; // { ms, gpio, value } of the output pins
    this.adcReads = []; // emulated ms of every ADC conversion started
    this.busyCycles = 0;
    this.boots = 0;
    this.flashStats = { erases: 0, programs: 0 };
    this.hung = false;
    this.pressed = new Set(); // buttons held down: 'btn_cw', 'btn_ccw'
    this.plantMs = 0;
    this.sensors = null;
    this.playsEl = Boolean(this.plant.playsEl);
    this.i2cLog = []; // register writes the magnetometer received
    // The relay outputs whose edges are recorded (and dropped by a reset).
    this.outputPins = [this.pins.az_cw, this.pins.az_ccw, this.pins.az_speed, this.pins.az_brake];
    if (this.playsEl) this.outputPins.push(this.pins.el_up, this.pins.el_down, this.pins.el_speed);
    this.resetMotion();
    this.ports = [makePort(), makePort()]; // log, protocol: stable across resets
    this.boot(0);
  }

  get nowNs() {
    return this.baseNs + this.rp.clock.nanos;
  }
  get nowMs() {
    return this.nowNs / 1e6;
  }

  boot(watchdogReason, keepScratch = true) {
    const previous = keepScratch ? this.rp : null;
    const rp = new RP2040();
    rp.logger = new ConsoleLogger(LogLevel.Error, true);
    // VREG_AND_CHIP_RESET is unimplemented and reads all ones: the bootrom
    // would see CHIP_RESET.PSM_RESTART_FLAG (a debugger's rescue request)
    // and park the core. A power-on reset reads 0 there.
    rp.peripherals[0x40064].readUint32 = () => 0;
    rp.peripherals[0x40064].writeUint32 = () => {};
    rp.loadBootrom(this.opts.bootrom); // resets the core from the bootrom's vectors; clears flash
    rp.flash.set(this.flash);
    const oldWatchdog = previous?.peripherals[0x40058];
    // The bootrom's "boot to an address" (scratch 4 = 0xb007c0d3), set by
    // its reset_usb_boot (the console's bootsel): through the bootrom's own
    // reset path, which takes the core into the USB bootloader.
    const romEntry = oldWatchdog && oldWatchdog.scratchData[4] === 0xb007c0d3;
    // Straight into boot2 at the start of flash, as rp2040js's own demo
    // does: the bootrom's flash boot reads boot2 through the SSI, which
    // rp2040js does not model. The bootrom stays for its ROM functions.
    if (!romEntry) rp.core.PC = 0x10000000;
    this.romEntry = romEntry;
    this.flash = rp.flash; // the chip's own array from now on (survives the next reset)
    installFlashModel(rp, this.flashStats);
    const watchdog = rp.peripherals[0x40058];
    if (previous) {
      const old = previous.peripherals[0x40058];
      watchdog.scratchData.set(old.scratchData);
      watchdog.reason = watchdogReason;
    }
    watchdog.onWatchdogTrigger = () => {
      this.resetPending = watchdog.reason || 1;
      // The chip resets here; rp2040js's counter would otherwise stay at 0
      // and fire again at once, for ever, within the same clock tick.
      watchdog.alarm.enable = false;
      watchdog.timer.enable = false;
    };
    this.rp = rp;
    this.resetPending = 0;
    this.boots++;
    this.hung = false;
    this.installPio(rp);
    this.installUsb(rp);
    this.installPins(rp);
    this.startMa3(rp, this.pins.az_ma3, () => this.sensors);
    if (this.playsEl) this.startMa3(rp, this.pins.el_ma3, () => this.sensors?.el);
    if (this.plant.hasMag) for (const i2c of rp.i2c) installQmc5883l(i2c, () => this.sensors?.magRegisters, this.i2cLog);
  }

  /**
   * Drive starts and reversals per axis, sampled every emulated millisecond
   * from the plant's inputs: a start is off -> on, a reversal a start (or a
   * switch without a stop) in the other direction than the last run.
   */
  resetMotion() {
    const axis = () => ({ dir: 0, lastRun: 0, starts: 0, reversals: 0 });
    this.motion = { az: axis(), el: axis() };
  }

  trackMotion(m, dir) {
    if (dir !== 0 && dir !== m.dir) {
      m.starts++;
      if (m.lastRun !== 0 && dir !== m.lastRun) m.reversals++;
      m.lastRun = dir;
    }
    m.dir = dir;
  }

  installPio(rp) {
    for (const pio of rp.pio) {
      pio.run = () => {}; // stepped below, on emulated time
      pio.lastNs = rp.clock.nanos;
      for (const m of pio.machines) m.stepAcc = 0;
    }
    const tick = () => {
      this.pioCatchUp();
      alarm.schedule(PIO_CATCH_UP_NS);
    };
    const alarm = rp.clock.createAlarm(tick);
    alarm.schedule(PIO_CATCH_UP_NS);
  }

  /** Runs each enabled state machine for the emulated time since the last call. */
  pioCatchUp() {
    const now = this.rp.clock.nanos;
    for (const pio of this.rp.pio) {
      const dt = now - pio.lastNs;
      pio.lastNs = now;
      if (pio.stopped || dt <= 0) continue;
      let stepped = false;
      for (const m of pio.machines) {
        if (!m.enabled) continue;
        const div = m.clockDivInt + m.clockDivFrac / 256 || 65536;
        m.stepAcc += dt / NS_PER_CYCLE / div;
        while (m.stepAcc >= 1) {
          m.step();
          m.stepAcc -= 1;
          stepped = true;
        }
      }
      if (stepped) pio.checkChangedPins();
    }
  }

  installUsb(rp) {
    const host = new UsbHost(rp.usbCtrl);
    this.usb = host;
    host.onPorts = (ports) => {
      ports.forEach((p, i) => this.ports[i]?.bind(p));
      this.ports[0].onData = (bytes) => {
        this.onLog(bytes);
        this.logTap?.(bytes);
      };
    };
    host.onConnected = () => {
      this.usbConnectedMs = this.nowMs;
    };
    for (const p of this.ports) p.unbind();
  }

  onLog(bytes) {
    const text = Buffer.from(bytes).toString('latin1');
    this.log += text;
    const parts = (this.partialLine + text).split('\n');
    this.partialLine = parts.pop();
    for (const line of parts) {
      const entry = { ms: this.nowMs, text: line.replace(/\r$/, '') };
      this.logLines.push(entry);
      if (this.opts.echoLog) console.log(`  [${entry.ms.toFixed(1).padStart(9)} ms] log: ${entry.text}`);
    }
  }

  installPins(rp) {
    for (const gpio of this.outputPins) {
      if (gpio < 0) continue;
      rp.gpio[gpio].addListener(() => {
        this.edges.push({ ms: this.nowMs, gpio, value: this.outputLevel(gpio) });
      });
    }
    const adc = rp.adc;
    const read = adc.onADCRead;
    // A pot's conversions within one plant step take its samples in turn
    // (each with its own noise when the plant gives several, --pot-samples).
    const turn = new Map();
    adc.onADCRead = (channel) => {
      this.adcReads.push(this.nowMs);
      const s = this.sensors;
      const samples =
        channel === adcChannel(this.pins.az_pot) ? s?.potSamples
        : channel === adcChannel(this.pins.el_pot) ? s?.el?.potSamples
        : undefined;
      if (samples?.length > 1) {
        const i = turn.get(channel) ?? 0;
        adc.channelValues[channel] = samples[i % samples.length];
        turn.set(channel, i + 1);
      }
      read(channel);
    };
    if (this.sensors) this.applySensors(this.sensors);
  }

  /** The level an output pin drives (false when it is not an output). */
  outputLevel(gpio) {
    const pin = this.rp.gpio[gpio];
    return pin.outputEnable && pin.outputValue;
  }

  /** The PWM duty of a pin in PWM mode, from its slice's registers. */
  duty(gpio) {
    const pin = this.rp.gpio[gpio];
    if (pin.functionSelect !== 4) return 0; // GPIO_FUNC_PWM
    const ch = this.rp.pwm.channels[(gpio >> 1) & 7];
    return pwmDuty(ch.csr, ch.cc, ch.top, gpio);
  }

  /** An MA3's waveform on its pin, frame after frame, from the plant's latest reading of that axis. */
  startMa3(rp, gpio, axisSensors) {
    if (gpio < 0) return;
    const pin = rp.gpio[gpio];
    let frame = null;
    const rise = rp.clock.createAlarm(() => {
      const s = axisSensors();
      frame = s ? ma3Frame(s.ma3Valid && this.ma3Connected !== false, s.ma3HighUs, s.ma3LowUs) : null;
      if (!frame) {
        rise.schedule(1_000_000);
        return;
      }
      this.pioCatchUp();
      pin.setInputValue(true);
      fall.schedule(frame.fallNs);
    });
    const fall = rp.clock.createAlarm(() => {
      this.pioCatchUp();
      pin.setInputValue(false);
      rise.schedule(frame.periodNs - frame.fallNs);
    });
    rise.schedule(1000);
  }

  applySensors(s) {
    const rp = this.rp;
    const ch = adcChannel(this.pins.az_pot);
    if (ch >= 0) rp.adc.channelValues[ch] = s.potCounts;
    const elCh = s.el ? adcChannel(this.pins.el_pot) : -1;
    if (elCh >= 0) rp.adc.channelValues[elCh] = s.el.potCounts;
    for (const [gpio, level] of switchLevels(this.pins, { ...s, buttons: this.pressed })) {
      if (rp.gpio[gpio].rawInputValue !== level) rp.gpio[gpio].setInputValue(level);
    }
  }

  plantInputs() {
    return plantInputs(this.pins, (g) => this.outputLevel(g), (g) => this.duty(g));
  }

  /** The elevation's drive from its pins (null when the plant plays the azimuth only). */
  elPlantInputs() {
    if (!this.playsEl) return null;
    return elPlantInputs(this.pins, (g) => this.outputLevel(g), (g) => this.duty(g));
  }

  /** Executes instructions until emulated time targetNs (or a reset). */
  runCpu(targetNs) {
    const rp = this.rp;
    const core = rp.core;
    const clock = rp.clock;
    const target = targetNs - this.baseNs;
    while (clock.nanos < target && !this.resetPending) {
      if (core.waiting || this.hung) {
        const next = clock.nextAlarm ? clock.nextAlarm.nanos : target;
        clock.tick(Math.max(0, Math.min(next, target) - clock.nanos));
      } else {
        const cycles = core.executeInstruction();
        this.busyCycles += cycles;
        clock.tick(cycles * NS_PER_CYCLE);
      }
    }
  }

  /** Advances emulated time by ms, the plant in 1 ms steps. */
  async run(ms) {
    const end = this.nowNs + ms * 1e6;
    while (this.nowNs < end - 1) {
      const sliceEnd = Math.min(end, (Math.floor(this.nowNs / 1e6) + 1) * 1e6);
      this.runCpu(sliceEnd);
      if (this.resetPending) {
        const reason = this.resetPending;
        this.resetAllOutputs();
        this.baseNs = this.nowNs;
        this.resets = (this.resets ?? 0) + 1;
        this.onReset?.(reason);
        this.usbConnectedMs = undefined;
        this.boot(reason);
        continue;
      }
      const plantMs = Math.floor(this.nowNs / 1e6);
      if (plantMs > this.plantMs) {
        const u = this.plantInputs();
        const uEl = this.elPlantInputs();
        this.trackMotion(this.motion.az, driveDirection(u));
        if (uEl) this.trackMotion(this.motion.el, driveDirection(uEl));
        this.sensors = await this.plant.step(plantMs, u, uEl ?? undefined);
        this.plantMs = plantMs;
        this.applySensors(this.sensors);
      }
    }
  }

  /**
   * newlib's malloc in the emulated RAM, read through the image's symbols:
   * `room` the bytes between the static RAM's end and the stack limit (all
   * the heap there is), `sbrked` what malloc has taken of it, `highWater`
   * the most it has used: the heap's RAM starts out zero and every chunk
   * malloc ever split off leaves a header behind, so the last non-zero byte
   * marks the highest its top chunk has been, however briefly. Null for an
   * image without these symbols (a .bin).
   */
  heap() {
    const sym = this.symbols();
    const need = ['end', '__StackLimit', '__malloc_max_sbrked_mem'];
    if (!sym || need.some((n) => !sym.has(n))) return null;
    const ram = 0x20000000;
    const end = sym.get('end').value;
    const limit = sym.get('__StackLimit').value;
    let last = end - ram;
    for (let i = limit - ram - 1; i >= end - ram; i--) {
      if (this.rp.sram[i] !== 0) {
        last = i + 1;
        break;
      }
    }
    return {
      room: limit - end,
      sbrked: this.rp.readUint32(sym.get('__malloc_max_sbrked_mem').value),
      highWater: last - (end - ram),
    };
  }

  symbols() {
    if (this.symbolCache === undefined)
      this.symbolCache = this.opts.image?.endsWith('.elf') ? elfSymbols(this.opts.image) : null;
    return this.symbolCache;
  }

  /** Runs until pred() holds, checking every step ms; false after timeoutMs of emulated time. */
  async runUntil(pred, timeoutMs, step = 5) {
    const end = this.nowMs + timeoutMs;
    while (this.nowMs < end) {
      if (pred()) return true;
      await this.run(step);
    }
    return pred();
  }

  /** The first log line matching re, from line `since` on (running up to timeoutMs for it); null if none. */
  async waitForLog(re, timeoutMs, since = 0) {
    let found = null;
    const ok = await this.runUntil(
      () => (found = this.logLines.slice(since).find((l) => re.test(l.text))) != null,
      timeoutMs,
    );
    return ok ? found : null;
  }

  /**
   * The log port as a CDC endpoint for a bridge (the console is served
   * there): what it prints still goes to the log as well.
   */
  logEndpoint() {
    const board = this;
    return {
      write: (bytes) => board.ports[0].write(bytes),
      set onData(fn) {
        board.logTap = fn;
      },
    };
  }

  /** Presses (true) or releases a push button ('btn_cw', 'btn_ccw'); applied at once. */
  press(button, down) {
    if (down) this.pressed.add(button);
    else this.pressed.delete(button);
    if (this.sensors) this.applySensors(this.sensors);
  }

  /**
   * A cup anemometer's reed contact to ground on `gpio` (pins.wind): closed
   * (low) for `closedMs` `hz` times a second, open (high: the pull-up, which
   * the emulator does not model) between; hz 0 leaves it open. On the
   * chip's own clock, as the MA3's frames, so the pulses fall between the
   * harness's millisecond steps as a real contact's would. Returns the
   * number of closures played so far through `board.anemometerPulses`.
   */
  anemometer(gpio, hz, closedMs = 5) {
    const rp = this.rp;
    const pin = rp.gpio[gpio];
    this.anemometerAlarms?.forEach((a) => a.cancel());
    this.anemometerAlarms = null;
    this.anemometerPulses ??= 0;
    pin.setInputValue(true);
    if (hz <= 0) return;
    const periodNs = 1e9 / hz;
    const closedNs = Math.min(closedMs * 1e6, periodNs / 2);
    const open = rp.clock.createAlarm(() => {
      pin.setInputValue(true);
      close.schedule(periodNs - closedNs);
    });
    const close = rp.clock.createAlarm(() => {
      this.anemometerPulses++;
      pin.setInputValue(false);
      open.schedule(closedNs);
    });
    close.schedule(periodNs - closedNs);
    this.anemometerAlarms = [open, close];
  }

  /** A reset puts every pin back to an input: the outputs drop. A log line cut by it ends there. */
  resetAllOutputs() {
    if (this.partialLine) this.onLog(new TextEncoder().encode(' [cut by the reset]\n'));
    for (const gpio of this.outputPins) {
      if (gpio >= 0 && this.outputLevel(gpio)) this.edges.push({ ms: this.nowMs, gpio, value: false });
    }
  }

  /** Power off and on: a new chip on the same flash (no watchdog state kept). */
  powerCycle() {
    this.resetAllOutputs();
    this.baseNs = this.nowNs;
    this.usbConnectedMs = undefined;
    this.boot(0, false);
  }

  /** Stops the core from the outside: no instruction runs, emulated time (timers, watchdog) goes on. */
  hang() {
    this.hung = true;
  }
}

/** A CDC port that outlives the chip: re-bound to the new device after a reset. */
function makePort() {
  const port = {
    target: null,
    onData: null,
    queued: [],
    bind(p) {
      port.target = p;
      p.onData = (bytes) => port.onData?.(bytes);
      if (port.queued.length) p.write(port.queued.splice(0));
    },
    unbind() {
      port.target = null;
    },
    write(bytes) {
      if (port.target) port.target.write(bytes);
      else port.queued.push(...bytes);
    },
  };
  return port;
}

/**
 * A QMC5883L (address 0x0D) on an emulated I2C block, answering from the
 * plant's latest registers (`registers()`, 14 bytes from 0x00): a write sets
 * the register pointer with its first byte, the bytes after it are register
 * writes (noted in `log`); a read returns registers from the pointer on.
 * Other addresses are not acknowledged.
 */
export function installQmc5883l(i2c, registers, log = []) {
  const kAddress = 0x0d;
  let pointer = 0;
  let pointerNext = false;
  i2c.onStart = () => i2c.completeStart();
  i2c.onConnect = (address, mode) => {
    pointerNext = mode === 0; // a write begins with the register pointer
    i2c.completeConnect(address === kAddress);
  };
  i2c.onWriteByte = (value) => {
    if (pointerNext) {
      pointer = value;
      pointerNext = false;
    } else {
      log.push({ register: pointer, value });
      pointer++;
    }
    i2c.completeWrite(true);
  };
  i2c.onReadByte = () => {
    const regs = registers();
    i2c.completeRead(regs && pointer < regs.length ? regs[pointer] : 0);
    pointer++;
  };
  i2c.onStop = () => i2c.completeStop();
}
