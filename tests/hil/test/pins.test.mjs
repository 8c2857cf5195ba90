// The plant on the pins, without the emulator: which GPIO carries what (the
// settings table's defaults), the relay and H-bridge outputs as the plant's
// inputs, the MA3 waveform for an angle, the pot's ADC code, the switches'
// polarity, and the settings slot the harness writes into the flash image.
import assert from 'node:assert/strict';
import { dirname, join } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';
import {
  crc32,
  readSettings,
  writeSettingsSlot,
  FLASH_BYTES,
  SETTINGS_REGION_BYTES,
} from '../lib/flash.mjs';
import {
  adcChannel,
  driveDirection,
  elPlantInputs,
  ma3DecodeDeg,
  ma3Frame,
  pinDefaults,
  plantInputs,
  potCountsToDeg,
  pwmDuty,
  switchLevels,
} from '../lib/pins.mjs';
import { installQmc5883l } from '../lib/board.mjs';
import { Plant } from '../lib/plant.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const root = process.env.ROTORD_ROOT ?? join(here, '../../..');
const binary = process.env.ROTORD_HIL_PLANT ?? join(root, 'build/tests/hil/rotord_hil_plant');
const pins = pinDefaults(root);
const off = { cw: 0, ccw: 0, fast: 0, brake: 0, pwmCw: 0, pwmCcw: 0 };

test('the pin map is the pins.* defaults of the settings table', () => {
  assert.deepEqual(
    [pins.az_cw, pins.az_ccw, pins.az_speed, pins.az_brake, pins.az_t1, pins.az_t2, pins.az_l1, pins.az_l2],
    [5, 6, 7, 8, 9, 10, 11, 12],
  );
  assert.deepEqual([pins.az_pwm_cw, pins.az_pwm_ccw, pins.az_ma3, pins.az_pot], [14, 15, 2, 26]);
  assert.equal(pins.btn_cw, -1); // buttons unwired by default
  assert.equal(adcChannel(pins.az_pot), 0);
  assert.equal(adcChannel(pins.el_pot), 1);
  assert.equal(adcChannel(pins.az_cw), -1);
});

test('relay levels and H-bridge duties become the plant inputs', () => {
  const high = new Set([pins.az_cw, pins.az_speed]);
  const u = plantInputs(pins, (g) => high.has(g), (g) => (g === pins.az_pwm_ccw ? 0.25 : 0));
  assert.deepEqual(u, { cw: 1, ccw: 0, fast: 1, brake: 0, pwmCw: 0, pwmCcw: 0.25 });
});

test('PWM duty from the slice registers: channel A on even pins, B on odd, 0 while disabled', () => {
  const cc = (300 << 16) | 500;
  assert.equal(pwmDuty(1, cc, 999, 14), 0.5);
  assert.equal(pwmDuty(1, cc, 999, 15), 0.3);
  assert.equal(pwmDuty(0, cc, 999, 14), 0);
  assert.equal(pwmDuty(1, 1000, 999, 14), 1);
});

test('the MA3 waveform for an angle decodes to that angle (12-bit, one count)', async () => {
  const plant = new Plant({ binary, profile: 'spid', thetaDeg: 0 });
  try {
    let ms = 1;
    for (const deg of [0.5, 90, 179.9, 271.3, 359.9]) {
      await plant.command(`set ${deg}`);
      const s = await plant.step(ms++, off);
      const frame = ma3Frame(s.ma3Valid, s.ma3HighUs, s.ma3LowUs);
      assert.ok(frame, `a frame at ${deg}`);
      assert.equal(frame.periodNs, 4098_000);
      assert.ok(Math.abs(ma3DecodeDeg(frame.fallNs / 1000, (frame.periodNs - frame.fallNs) / 1000) - deg) <= 360 / 4096, `${deg}`);
    }
    assert.equal(ma3Frame(false, 100, 3998), null); // no signal: the pin stays low
  } finally {
    plant.close();
  }
});

test('the pot reads back through the firmware default calibration (ADC 12 bits over 3.3 V)', async () => {
  const plant = new Plant({ binary, profile: 'g5500', thetaDeg: 0 });
  try {
    let ms = 1;
    for (const deg of [0, 100, 225, 449]) {
      await plant.command(`set ${deg}`);
      const s = await plant.step(ms++, off);
      assert.ok(s.potCounts >= 0 && s.potCounts <= 4095);
      assert.ok(Math.abs(potCountsToDeg(s.potCounts) - deg) < 0.2, `${deg}: ${s.potCounts}`);
    }
  } finally {
    plant.close();
  }
});

test('switches and buttons pull their pin low when closed (the input has a pull-up)', async () => {
  const plant = new Plant({ binary, profile: 'g5500', thetaDeg: 200 });
  try {
    let s = await plant.step(1, off);
    let levels = switchLevels(pins, s);
    assert.equal(levels.get(pins.az_l2), true); // open: high
    assert.equal(levels.get(pins.az_l1), true);
    await plant.command('limit cw 1 -1');
    s = await plant.step(2, off);
    levels = switchLevels(pins, s);
    assert.equal(levels.get(pins.az_l2), false); // the CW end switch closed: low
    assert.equal(levels.get(pins.az_l1), true);
    // The overlap switch T1 closes above 360 deg on the 450 deg G-5500.
    await plant.command('clear');
    await plant.command('set 400');
    s = await plant.step(3, off);
    assert.equal(switchLevels(pins, s).get(pins.az_t1), false);
    // Buttons are unwired by default; wired, a pressed one reads low too.
    assert.equal(switchLevels(pins, { ...s, buttons: new Set(['btn_cw']) }).has(4), false);
    const wired = { ...pins, btn_cw: 4, btn_ccw: 13 };
    const levels2 = switchLevels(wired, { ...s, buttons: new Set(['btn_cw']) });
    assert.equal(levels2.get(4), false);
    assert.equal(levels2.get(13), true);
  } finally {
    plant.close();
  }
});

test('the plant turns from the pins: CW relay, then H-bridge duty, and stalls on a jam', async () => {
  const relay = new Plant({ binary, profile: 'g5500', thetaDeg: 100 });
  const bridge = new Plant({ binary, profile: 'spid', thetaDeg: 100 });
  try {
    const r = await relay.step(1000, { ...off, cw: 1 });
    assert.ok(r.thetaDeg > 103 && r.thetaDeg < 106, `${r.thetaDeg}`); // 6 deg/s after 10 ms relay delay and tau
    const b = await bridge.step(1000, { ...off, pwmCcw: 0.8 });
    assert.ok(b.thetaDeg < 98, `${b.thetaDeg}`);
    await relay.command('jam -1');
    const j = await relay.step(1200, { ...off, cw: 1 });
    assert.ok(j.stalled);
  } finally {
    relay.close();
    bridge.close();
  }
});

test('a two-speed or voltage-select drive (--drive): FAST turns at full speed, without it at half', async () => {
  for (const drive of ['relay_two_speed', 'relay_voltage_select']) {
    const plant = new Plant({ binary, profile: 'g5500', thetaDeg: 100, drive });
    try {
      assert.match(await plant.settingsDocument({}), new RegExp(`"az.drive": "${drive}"`));
      const slow0 = await plant.step(1000, { ...off, cw: 1 });
      const slow1 = await plant.step(2000, { ...off, cw: 1 });
      const fast1 = await plant.step(3000, { ...off, cw: 1, fast: 1 });
      const fast2 = await plant.step(4000, { ...off, cw: 1, fast: 1 });
      const slowDegS = slow1.thetaDeg - slow0.thetaDeg;
      const fastDegS = fast2.thetaDeg - fast1.thetaDeg;
      assert.ok(Math.abs(slowDegS - 3) < 0.1 && Math.abs(fastDegS - 6) < 0.1, `${drive}: ${slowDegS} then ${fastDegS} deg/s`);
    } finally {
      plant.close();
    }
  }
});

test('a failed sensor: lost, the pot reads 0 and the MA3 sends no frame; stuck, both hold while the plant turns; a noise burst', async () => {
  const plant = new Plant({ binary, profile: 'g5500', thetaDeg: 100 });
  try {
    const before = await plant.step(10, off);
    assert.ok(before.potCounts > 0 && before.ma3Valid);
    await plant.command('sensor loss -1');
    const lost = await plant.step(20, off);
    assert.equal(lost.potCounts, 0);
    assert.equal(ma3Frame(lost.ma3Valid, lost.ma3HighUs, lost.ma3LowUs), null);
    await plant.command('clear');
    await plant.command('sensor stuck -1');
    const stuck = await plant.step(2000, { ...off, cw: 1 });
    assert.ok(stuck.thetaDeg > 105, `${stuck.thetaDeg}`); // the rotator turned
    assert.equal(stuck.potCounts, before.potCounts);
    assert.equal(stuck.ma3HighUs, before.ma3HighUs);
    await plant.command('clear');
    const cleared = await plant.step(2010, off);
    assert.ok(Math.abs(potCountsToDeg(cleared.potCounts) - cleared.thetaDeg) < 0.2, `${cleared.potCounts} at ${cleared.thetaDeg}`);
    // A noise burst: 60 deg rms on the MA3 (a code per 4.1 ms frame) for 1 s.
    await plant.command('sensor burst 60 1');
    let widest = 0;
    for (let ms = 2020; ms < 2200; ms += 10) {
      const b = await plant.step(ms, off);
      const deg = ma3DecodeDeg(b.ma3HighUs, b.ma3LowUs);
      widest = Math.max(widest, Math.abs(((deg - b.thetaDeg + 540) % 360) - 180));
    }
    assert.ok(widest > 30, `${widest}`);
    await assert.rejects(plant.command('sensor melted 1'), /error: sensor/);
    await assert.rejects(plant.command('sensor burst -5 1'), /error: sensor/);
  } finally {
    plant.close();
  }
});

test('the magnetometer (--mag): the QMC5883L registers for the angle, served over an I2C block', async () => {
  const plant = new Plant({ binary, profile: 'g5500', thetaDeg: 90, mag: true });
  try {
    const s = await plant.step(10, off);
    const regs = s.magRegisters;
    // x = 300 + 1200 cos 90, y = -150 + 900 sin 90, z = 400; DRDY; chip id 0xFF.
    assert.deepEqual([regs.readInt16LE(0), regs.readInt16LE(2), regs.readInt16LE(4), regs[6], regs[13]], [300, 750, 400, 1, 0xff]);
    // An I2C block's callbacks, as rp2040js calls them for the firmware's
    // transfers: a register write, then a burst read from 0x00.
    const done = [];
    const i2c = {
      completeStart: () => done.push('start'),
      completeConnect: (ack) => done.push(ack ? 'ack' : 'nack'),
      completeWrite: (ack) => done.push(ack ? 'w' : 'wnack'),
      completeRead: (v) => done.push(v),
      completeStop: () => done.push('stop'),
    };
    const log = [];
    installQmc5883l(i2c, () => regs, log);
    i2c.onStart(false);
    i2c.onConnect(0x1e, 0); // another address: not acknowledged
    i2c.onStop();
    i2c.onStart(false);
    i2c.onConnect(0x0d, 0);
    i2c.onWriteByte(0x09);
    i2c.onWriteByte(0x15);
    i2c.onStop();
    i2c.onStart(false);
    i2c.onConnect(0x0d, 0);
    i2c.onWriteByte(0x00);
    i2c.onStart(true);
    i2c.onConnect(0x0d, 1);
    for (let n = 0; n < 7; n++) i2c.onReadByte(n < 6);
    i2c.onStop();
    assert.deepEqual(log, [{ register: 0x09, value: 0x15 }]);
    assert.deepEqual(done, ['start', 'nack', 'stop', 'start', 'ack', 'w', 'w', 'stop', 'start', 'ack', 'w', 'start', 'ack', ...regs.subarray(0, 7), 'stop']);
  } finally {
    plant.close();
  }
});

test('the settings document for a profile, in a flash slot the firmware reads', async () => {
  const plant = new Plant({ binary, profile: 'spid', sensor: 'ma3' });
  try {
    const doc = await plant.settingsDocument({ 'usb.personality': 'easycomm' });
    const parsed = JSON.parse(doc);
    assert.equal(parsed['az.drive'], 'hbridge');
    assert.equal(parsed['az.sensor'], 'ma3');
    assert.equal(parsed['usb.personality'], 'easycomm');
    await assert.rejects(plant.settingsDocument({ 'no.such': 1 }), /unknown setting/);
    assert.equal(crc32(new TextEncoder().encode('123456789')), 0xcbf43926);
    const flash = new Uint8Array(FLASH_BYTES).fill(0xff);
    writeSettingsSlot(flash, doc, { slot: 1, sequence: 7 });
    assert.deepEqual(readSettings(flash), { slot: 1, sequence: 7, document: doc });
    // A flipped payload bit (slot 1 is the second half of the region) invalidates the slot.
    flash[FLASH_BYTES - SETTINGS_REGION_BYTES / 2 + 256] ^= 1;
    assert.equal(readSettings(flash), null);
  } finally {
    plant.close();
  }
});

test('the elevation pins: UP/DOWN relays and H-bridge into the plant, its end switches, its pot on ADC 1', async () => {
  assert.deepEqual(
    [pins.el_up, pins.el_down, pins.el_speed, pins.el_pwm_up, pins.el_pwm_down, pins.el_ma3, pins.el_pot],
    [16, 17, 18, 20, 21, 3, 27],
  );
  const high = new Set([pins.el_down]);
  const u = plantInputs(pins, (g) => high.has(g), () => 0);
  const e = elPlantInputs(pins, (g) => high.has(g), (g) => (g === pins.el_pwm_up ? 0.5 : 0));
  assert.deepEqual(u, off); // the azimuth's pins are untouched
  assert.deepEqual(e, { cw: 0, ccw: 1, fast: 0, brake: 0, pwmCw: 0.5, pwmCcw: 0 });
  assert.equal(driveDirection({ ...off, cw: 1 }), 1);
  assert.equal(driveDirection({ ...off, pwmCcw: 0.3 }), -1);
  assert.equal(driveDirection(off), 0);
  const plant = new Plant({ binary, profile: 'g5500', thetaDeg: 200, elSensor: 'pot', elThetaDeg: 10 });
  try {
    const s = await plant.step(1000, off, { ...off, cw: 1 }); // UP for a second
    assert.ok(s.el.thetaDeg > 11 && s.el.thetaDeg < 13, `${s.el.thetaDeg}`); // 2.7 deg/s
    assert.equal(s.thetaDeg, 200);
    assert.ok(Math.abs(potCountsToDeg(s.el.potCounts, { counts: 62, deg: 0 }, { counts: 3723, deg: 180 }) - s.el.thetaDeg) < 0.1);
    const levels = switchLevels(pins, s);
    assert.equal(levels.get(pins.el_limit_up), true); // open
    assert.equal(levels.get(pins.el_limit_down), true);
    const doc = JSON.parse(await plant.settingsDocument());
    assert.equal(doc['el.enabled'], true);
  } finally {
    plant.close();
  }
});

test('noise: seeded (two plants read the same), a fresh draw for every conversion of a step', async () => {
  const opts = { binary, profile: 'g5500', thetaDeg: 200, noise: true, potSamples: 8 };
  const a = new Plant(opts);
  const b = new Plant(opts);
  try {
    const sa = await a.step(1, off);
    const sb = await b.step(1, off);
    assert.equal(sa.potSamples.length, 8);
    assert.deepEqual(sa.potSamples, sb.potSamples);
    assert.ok(new Set(sa.potSamples).size > 1, `${sa.potSamples}`);
    assert.ok(sa.potSamples.every((c) => Math.abs(potCountsToDeg(c) - 200) < 2));
  } finally {
    a.close();
    b.close();
  }
});
