// The rotator on the chip's pins: which GPIO carries what (the pins.*
// settings' defaults, read from the settings table itself), and how the
// plant's quantities become pin levels, ADC codes and the MA3's waveform.
// Pure functions: unit-tested without the emulator (test/pins.test.mjs).
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

/** The default of every pins.* setting, e.g. { az_cw: 5, az_pot: 26, btn_cw: -1 }. */
export function pinDefaults(root) {
  const table = readFileSync(join(root, 'core/settings/settings_table.def'), 'utf8');
  const pins = {};
  // SETTING(kPinAzCw, "pins.az_cw", kInt, "GPIO", -1, 28, 5, ...
  const re = /SETTING\(\s*\w+,\s*"pins\.(\w+)",\s*\w+,\s*"[^"]*",\s*(-?[\d.]+),\s*(-?[\d.]+),\s*(-?[\d.]+)/g;
  for (const m of table.matchAll(re)) pins[m[1]] = Number(m[4]);
  return pins;
}

/** ADC input of a GPIO (26..29 are ADC 0..3), or -1. */
export function adcChannel(gpio) {
  return gpio >= 26 && gpio <= 29 ? gpio - 26 : -1;
}

/** The RP2040's ADC: 12 bits over 3.3 V (sim/adc_scale.hpp). */
export const ADC_VREF_V = 3.3;
export const ADC_FULL_SCALE = 4095;
export function adcCounts(volts) {
  return Math.max(0, Math.min(ADC_FULL_SCALE, Math.round((volts / ADC_VREF_V) * ADC_FULL_SCALE)));
}

/**
 * Limit, overlap and button contacts switch to ground against the pin's
 * pull-up (ports/pico_w/pico_hal.hpp, PicoSwitch): closed reads low. The
 * emulator models no pull-ups, so the harness drives the level itself.
 */
export function switchLevel(closed) {
  return !closed;
}

/**
 * The MA3's output for one frame as the plant reports it (high and low time
 * in microseconds) as edge times in nanoseconds from the frame's start:
 * rising at 0, falling at high, next rising at high + low. No signal
 * (unplugged encoder): null, the pin stays low.
 */
export function ma3Frame(valid, highUs, lowUs) {
  if (!valid || highUs <= 0 || lowUs <= 0) return null;
  return { fallNs: highUs * 1000, periodNs: (highUs + lowUs) * 1000 };
}

/** What the firmware makes of a frame (core: code = t_on * 4098 / period - 1), in degrees. */
export function ma3DecodeDeg(highUs, lowUs) {
  const code = Math.round((highUs * 4098) / (highUs + lowUs)) - 1;
  return (code * 360) / 4096;
}

/**
 * The firmware's default pot calibration (az.pot_cal_*: 62 counts = 0 deg,
 * 3723 counts = 450 deg), for reading a code back as an angle.
 */
export function potCountsToDeg(counts, lo = { counts: 62, deg: 0 }, hi = { counts: 3723, deg: 450 }) {
  return lo.deg + ((counts - lo.counts) * (hi.deg - lo.deg)) / (hi.counts - lo.counts);
}

/**
 * The plant's inputs from the pins: relay levels and H-bridge duties, in the
 * order rotord_hil_plant's `s` command takes them. `level(gpio)` is the
 * driven output level (false when not an output), `duty(gpio)` the PWM duty
 * 0..1 of a pin in PWM mode.
 */
export function plantInputs(pins, level, duty) {
  const on = (gpio) => (gpio >= 0 && level(gpio) ? 1 : 0);
  const pwm = (gpio) => (gpio >= 0 ? duty(gpio) : 0);
  return {
    cw: on(pins.az_cw),
    ccw: on(pins.az_ccw),
    fast: on(pins.az_speed),
    brake: on(pins.az_brake),
    pwmCw: pwm(pins.az_pwm_cw),
    pwmCcw: pwm(pins.az_pwm_ccw),
  };
}

/**
 * The elevation's plant inputs (played with the plant's --el): UP is the
 * elevation's forward (the plant's CW), DOWN its reverse; it has no brake.
 */
export function elPlantInputs(pins, level, duty) {
  const on = (gpio) => (gpio >= 0 && level(gpio) ? 1 : 0);
  const pwm = (gpio) => (gpio >= 0 ? duty(gpio) : 0);
  return {
    cw: on(pins.el_up),
    ccw: on(pins.el_down),
    fast: on(pins.el_speed),
    brake: 0,
    pwmCw: pwm(pins.el_pwm_up),
    pwmCcw: pwm(pins.el_pwm_down),
  };
}

/**
 * The direction a drive's inputs command: 1 forward (CW, up), -1 reverse,
 * 0 off. What the harness counts starts and reversals from.
 */
export function driveDirection(u) {
  const fwd = u.cw || u.pwmCw > 0;
  const rev = u.ccw || u.pwmCcw > 0;
  return fwd && !rev ? 1 : rev && !fwd ? -1 : 0;
}

/** The switch pins' levels from the plant's reply and the pressed buttons (unwired pins left out; the elevation's when the reply has one). */
export function switchLevels(pins, sw) {
  const out = new Map();
  const put = (gpio, closed) => {
    if (gpio >= 0) out.set(gpio, switchLevel(closed));
  };
  put(pins.az_l2, sw.limitCw); // L2: the CW end
  put(pins.az_l1, sw.limitCcw); // L1: the CCW end
  put(pins.az_t1, sw.t1);
  put(pins.az_t2, sw.t2);
  // Push buttons to ground, as the switches (the harness presses them).
  put(pins.btn_cw, sw.buttons?.has('btn_cw') ?? false);
  put(pins.btn_ccw, sw.buttons?.has('btn_ccw') ?? false);
  if (sw.el) {
    put(pins.el_limit_up, sw.el.limitCw);
    put(pins.el_limit_down, sw.el.limitCcw);
  }
  return out;
}

/**
 * Duty of a GPIO from the PWM slice's registers (slice = (gpio >> 1) & 7,
 * channel A on even pins): CC / (TOP + 1), 0 while the slice is disabled.
 */
export function pwmDuty(csr, cc, top, gpio) {
  if (!(csr & 1)) return 0;
  const level = gpio & 1 ? cc >>> 16 : cc & 0xffff;
  return Math.min(1, level / ((top & 0xffff) + 1));
}
