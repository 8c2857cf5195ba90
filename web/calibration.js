// Live calibration cards of the settings page: raw sensor readings next to
// the angle, and the buttons that turn "the antenna points at X now" into
// calibration settings. It names the calibration rows it writes (pot table,
// MA3 direction, magnetometer extremes); everything else on the page comes
// from the schema. Every write goes through the server (POST /api/settings,
// or the known bearing below), so its checks (ranges, a monotonic pot table)
// decide and a refusal saves nothing. An absolute sensor's zero (the MA3's, the magnetometer's heading
// offset) is the controller's known bearing (docs/commissioning.md): the
// card gives the bearing and accepts the proposal (POST /api/commission,
// then /api/commission/accept), so the arithmetic lives in one place.
//
// Angles: the controller shows sensor angle + <axis>.offset_deg, and the
// calibration rows are in the sensor's frame. "Antenna now at X" therefore
// stores X - offset, as the GS-232 O/F commands do.
'use strict';

const rotordCalibration = (() => {
  const MAX_POINTS = 8;  // point 1, six extra points, point 2 (pot_calibration.hpp)
  const NAMES = { az: 'Azimuth', el: 'Elevation' };

  function el(tag, attrs, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'class') e.className = v;
      else if (v !== undefined && v !== null && v !== false) e.setAttribute(k, v === true ? '' : v);
    }
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }
  const wrap360 = (d) => ((d % 360) + 360) % 360;
  const round = (v, digits) => Math.round(v * 10 ** digits) / 10 ** digits;
  const fmt = (v, digits) => rotord.fmt(v, digits);

  /**
   * ctx: {box, msg, values() -> the settings last loaded, report(r, okText),
   * reload() -> reloads the settings (and the form)}.
   */
  function create(ctx) {
    const cards = {};   // axis -> {update(status)}
    let status = null;  // the latest live status
    let shownValues = null;
    let shownShape = '';
    const spins = {};   // magnetometer spin calibration in progress, by axis

    const v = (key) => ctx.values()[key];
    const offset = (axis) => Number(v(axis + '.offset_deg')) || 0;

    /** POSTs calibration settings; a refusal is shown in `errorBox`, nothing is saved. */
    async function save(body, errorBox, okText, path = '/api/settings') {
      errorBox.textContent = '';
      const r = await rotord.post(path, body);
      if (r.status === 200) {
        ctx.report(r, okText);
        await ctx.reload();
        refresh(true);
        return true;
      }
      const errors = (r.body && r.body.errors) || {};
      const reasons = [...new Set(Object.values(errors))];
      const why = reasons.length ? reasons.join('; ') : (r.body && r.body.error) || `error ${r.status}`;
      errorBox.textContent = `Not saved: ${why}`;
      rotord.message(ctx.msg, `not saved: ${why}`, false);
      return false;
    }

    /** The angle the user entered in `input` (antenna frame), or null. */
    function entered(input) {
      const t = input.value.trim();
      const n = Number(t);
      if (t === '' || !isFinite(n)) {
        rotord.message(ctx.msg, 'enter the angle the antenna points at now', false);
        return null;
      }
      return n;
    }

    function liveSpan(label, id) {
      const s = el('span', { id });
      s.textContent = '–';
      return [el('span', {}, label, s), s];
    }

    function angleInput(axis) {
      const at = el('input', { type: 'number', step: 'any', inputmode: 'decimal', id: `cal-${axis}-deg`,
        'aria-label': 'angle the antenna points at now' });
      if (status && status[axis]) at.value = Math.round(status[axis].position_deg);
      return at;
    }

    // --- potentiometer: two points and the multi-point table -----------------
    function potPoints(axis) {
      const p = (which) => ({ counts: Number(v(`${axis}.pot_cal_${which}_counts`)),
        deg: Number(v(`${axis}.pot_cal_${which}_deg`)) });
      const list = [{ ...p('lo'), role: 'lo' }];
      const mids = Number(v(`${axis}.pot_cal_mid_points`)) || 0;
      for (let k = 1; k <= mids; ++k) list.push({ ...p('m' + k), role: 'm' + k });
      list.push({ ...p('hi'), role: 'hi' });
      return list;  // in table order: point 1, extra points, point 2
    }

    /** The settings body for a table in order: first = lo, last = hi, the rest m1.. */
    function potBody(axis, list) {
      const body = {};
      const put = (which, pt) => {
        body[`${axis}.pot_cal_${which}_counts`] = round(pt.counts, 1);
        body[`${axis}.pot_cal_${which}_deg`] = round(pt.deg, 3);
      };
      put('lo', list[0]);
      put('hi', list[list.length - 1]);
      for (let k = 1; k < list.length - 1; ++k) put('m' + k, list[k]);
      body[`${axis}.pot_cal_mid_points`] = list.length - 2;
      return body;
    }

    function potCard(axis, card) {
      const s = status[axis];
      const [rawEl, raw] = liveSpan('raw ', `cal-${axis}-raw`);
      const [voltsEl, volts] = liveSpan('', `cal-${axis}-volts`);
      const [degEl, deg] = liveSpan('angle ', `cal-${axis}-angle`);
      card.append(el('div', { class: 'live' }, rawEl, voltsEl, degEl));
      const at = angleInput(axis);
      const error = el('div', { class: 'cal-error', id: `cal-${axis}-error`, role: 'alert' });
      const button = (id, text) => el('button', { type: 'button', id: `cal-${axis}-${id}` }, text);
      const lo = button('lo', 'Set as low point');
      const hi = button('hi', 'Set as high point');
      const add = button('add', 'Add as point');
      card.append(el('div', { class: 'buttons' },
        el('label', {}, 'antenna now at ', at, ' °'), lo, hi, add));

      const live = () => status && status[axis];
      const setEnd = async (which) => {
        const angle = entered(at);
        if (angle === null || !live()) return;
        const counts = round(live().raw, 1);
        const body = {};
        body[`${axis}.pot_cal_${which}_counts`] = counts;
        body[`${axis}.pot_cal_${which}_deg`] = round(angle - offset(axis), 3);
        await save(body, error,
          `${NAMES[axis]}: ${which === 'lo' ? 'low' : 'high'} point set to ${counts} counts = ${angle}°`);
      };
      lo.addEventListener('click', () => setEnd('lo'));
      hi.addEventListener('click', () => setEnd('hi'));
      add.addEventListener('click', async () => {
        const angle = entered(at);
        if (angle === null || !live()) return;
        const list = potPoints(axis);
        if (list.length >= MAX_POINTS) {
          error.textContent = `The table is full (${MAX_POINTS} points): remove one first.`;
          return;
        }
        const point = { counts: round(live().raw, 1), deg: angle - offset(axis) };
        // Keep the table in counts order from point 1 to point 2; a point
        // beyond either end becomes the new end point.
        const rising = list[list.length - 1].counts >= list[0].counts;
        let where = list.findIndex((p) => (rising ? p.counts > point.counts : p.counts < point.counts));
        if (where < 0) where = list.length;
        list.splice(where, 0, point);
        await save(potBody(axis, list), error, `${NAMES[axis]}: point added, ${point.counts} counts = ${angle}°`);
      });

      const table = el('table', { class: 'points', id: `cal-${axis}-points` });
      const note = el('p', { class: 'note' });
      card.append(table, note, error);
      const render = () => {
        const list = potPoints(axis);
        const sorted = [...list].sort((a, b) => a.counts - b.counts);
        // Volts per count, from the live reading (the ADC's reference / full scale).
        const ref = s.raw_volts !== null && s.raw ? s.raw_volts / s.raw : null;
        table.textContent = '';
        table.append(el('thead', {}, el('tr', {}, el('th', {}, 'point'), el('th', {}, 'counts'),
          el('th', {}, 'V'), el('th', {}, 'angle °'), el('th', {}))));
        const body = el('tbody');
        for (const p of sorted) {
          const remove = el('button', { type: 'button', class: 'remove', 'data-role': p.role,
            'aria-label': `remove point ${p.role}`, disabled: list.length <= 2 }, '✕');
          remove.addEventListener('click', async () => {
            const rest = potPoints(axis).filter((q) => q.role !== p.role);
            await save(potBody(axis, rest), error, `${NAMES[axis]}: point removed`);
          });
          const name = p.role === 'lo' ? 'low' : p.role === 'hi' ? 'high' : 'extra ' + p.role.slice(1);
          body.append(el('tr', { 'data-role': p.role }, el('td', {}, name), el('td', {}, fmt(p.counts, 1)),
            el('td', {}, ref !== null ? fmt(p.counts * ref, 3) : '–'),
            el('td', {}, fmt(p.deg + offset(axis), 2)), el('td', {}, remove)));
        }
        table.append(body);
        const off = offset(axis);
        note.textContent = (off ? `Angles include ${axis}.offset_deg (${off}°); the settings store them without it. ` : '') +
          `${list.length} of ${MAX_POINTS} points; counts and angles must rise or fall together.`;
      };
      render();
      return {
        update(st) {
          const a = st[axis];
          raw.textContent = `${fmt(a.raw, 1)} ${a.raw_unit}`;
          volts.textContent = a.raw_volts === null ? '' : `${fmt(a.raw_volts, 3)} V`;
          deg.textContent = `${fmt(a.position_deg, 1)}°`;
        },
      };
    }

    // --- the known bearing: the controller's arithmetic, not the page's
    async function bearing(axis, angle, errorBox, okText) {
      // A bearing in 0..360: the controller turns the shortest way from its reading.
      const body = { axis, step: 'bearing', bearing_deg: round(wrap360(angle), 3) };
      let r = await rotord.post('/api/commission', body);
      // Refused until the controller has read the settings saved just now.
      for (let n = 0; n < 20 && /just changed/.test(r.body.error); ++n) {
        await new Promise((done) => setTimeout(done, 50));
        r = await rotord.post('/api/commission', body);
      }
      // Proposed (the card's note shows the value in force): accepted at once.
      if (r.status === 200) return save({}, errorBox, okText, '/api/commission/accept');
      errorBox.textContent = 'Not saved: ' + r.body.error;
    }
    const onBearing = (axis, at, errorBox, what) => () => {
      const angle = entered(at);
      if (angle !== null) bearing(axis, angle, errorBox, `${NAMES[axis]}: this ${what} is now ${angle}°`);
    };

    // --- MA3 absolute encoder: zero and direction ---------------------------
    function ma3Card(axis, card) {
      const [rawEl, raw] = liveSpan('code ', `cal-${axis}-raw`);
      const [dutyEl, duty] = liveSpan('duty ', `cal-${axis}-duty`);
      const [degEl, deg] = liveSpan('angle ', `cal-${axis}-angle`);
      card.append(el('div', { class: 'live' }, rawEl, dutyEl, degEl));
      const at = angleInput(axis);
      const error = el('div', { class: 'cal-error', id: `cal-${axis}-error`, role: 'alert' });
      const zero = el('button', { type: 'button', id: `cal-${axis}-zero` }, 'Set this position');
      const reverse = el('input', { type: 'checkbox', id: `cal-${axis}-reverse` });
      reverse.checked = !!v(`${axis}.ma3_reverse`);
      const zeroNow = el('p', { class: 'note', id: `cal-${axis}-zero-now` });
      const label = () => {
        zero.textContent = `Set this position as ${at.value.trim() === '' ? 'N' : at.value.trim()}°`;
      };
      at.addEventListener('input', label);
      card.append(el('div', { class: 'buttons' }, el('label', {}, 'antenna now at ', at, ' °'), zero),
        el('div', { class: 'buttons' }, el('label', {}, reverse, ' counts down when turning ',
          axis === 'az' ? 'clockwise' : 'up')),
        zeroNow, error);
      zero.addEventListener('click', onBearing(axis, at, error, 'position'));
      // Flipping the direction keeps the angle here: the reading before is the bearing.
      reverse.addEventListener('change', async () => {
        if (!status || !status[axis].valid) return;
        const keep = round(status[axis].position_deg, 2);
        const rev = reverse.checked;
        const turned = `${NAMES[axis]}: encoder direction ${rev ? 'reversed' : 'normal'}`;
        if (!(await save({ [`${axis}.ma3_reverse`]: rev }, error, turned))) {
          reverse.checked = !rev;
          return;
        }
        // The card was drawn again: its new error box.
        bearing(axis, keep, cards[axis].error, `${turned}, still ${keep}°`);
      });
      return {
        error,
        update(st) {
          const a = st[axis];
          const full = a.raw_full_scale;
          raw.textContent = full ? `${fmt(a.raw, 0)} of ${full}` : fmt(a.raw, 0);
          duty.textContent = full ? `${fmt((100 * (a.raw + 1)) / (full + 1), 1)} %` : '–';
          deg.textContent = `${fmt(a.position_deg, 1)}°`;
          label();
          zeroNow.textContent =
            `${axis}.ma3_zero_deg = ${fmt(Number(v(axis + '.ma3_zero_deg')), 2)}°`;
        },
      };
    }
    // --- magnetometer: raw field and the spin calibration -----------------------
    function magCard(axis, card) {
      const [xyEl, xy] = liveSpan('raw ', `cal-${axis}-mag`);
      const [degEl, deg] = liveSpan('angle ', `cal-${axis}-angle`);
      card.append(el('div', { class: 'live' }, xyEl, degEl));
      const error = el('div', { class: 'cal-error', id: `cal-${axis}-error`, role: 'alert' });
      const start = el('button', { type: 'button', id: `cal-${axis}-spin` }, 'Start spin calibration');
      const done = el('button', { type: 'button', id: `cal-${axis}-spin-save`, hidden: true }, 'Save');
      const cancel = el('button', { type: 'button', id: `cal-${axis}-spin-cancel`, hidden: true }, 'Cancel');
      const range = el('p', { class: 'note', id: `cal-${axis}-spin-range` });
      // After the spin: where the boom points (the sensor's north is seldom the boom's).
      const at = angleInput(axis);
      const align = el('button', { type: 'button', id: `cal-${axis}-align` }, 'Set this heading');
      const alignNow = el('p', { class: 'note', id: `cal-${axis}-align-now` });
      const label = () => {
        align.textContent = `Set this heading as ${at.value.trim() === '' ? 'N' : at.value.trim()}°`;
      };
      at.addEventListener('input', label);
      card.append(el('div', { class: 'buttons' }, start, done, cancel), range,
        el('div', { class: 'buttons' }, el('label', {}, 'antenna now at ', at, ' °'), align), alignNow, error);
      align.addEventListener('click', onBearing(axis, at, error, 'heading'));
      const current = () => `x ${v('mag.x_min')} … ${v('mag.x_max')}, y ${v('mag.y_min')} … ${v('mag.y_max')}`;
      const show = () => {
        const spin = spins[axis];
        start.hidden = !!spin;
        done.hidden = cancel.hidden = !spin;
        if (!spin) {
          range.textContent = `Saved: ${current()}. Start, turn the rotator through a full circle ` +
            '(control page or its own buttons), then save.';
        } else if (spin.n === 0) {
          range.textContent = 'Recording… no sample yet.';
        } else {
          range.textContent = `Recording (${spin.n} samples): x ${spin.x_min} … ${spin.x_max}, ` +
            `y ${spin.y_min} … ${spin.y_max}. Turn a full circle, then save.`;
        }
        done.disabled = !spin || !(spin.x_max > spin.x_min && spin.y_max > spin.y_min);
      };
      start.addEventListener('click', () => {
        spins[axis] = { n: 0, x_min: Infinity, x_max: -Infinity, y_min: Infinity, y_max: -Infinity };
        error.textContent = '';
        show();
      });
      cancel.addEventListener('click', () => { delete spins[axis]; show(); });
      done.addEventListener('click', async () => {
        const spin = spins[axis];
        const body = { 'mag.x_min': spin.x_min, 'mag.x_max': spin.x_max,
          'mag.y_min': spin.y_min, 'mag.y_max': spin.y_max };
        if (await save(body, error, 'magnetometer calibration saved')) { delete spins[axis]; show(); }
      });
      show();
      return {
        update(st) {
          const a = st[axis];
          const m = a.mag;
          xy.textContent = m ? `x ${m.x}, y ${m.y}, z ${m.z}` : 'no sample (the chip does not answer)';
          deg.textContent = a.valid ? `${fmt(a.position_deg, 1)}°` : '–';
          label();
          alignNow.textContent = `mag.declination_deg = ${fmt(Number(v('mag.declination_deg')) || 0, 2)}°`;
          const spin = spins[axis];
          if (spin && m) {
            spin.n += 1;
            spin.x_min = Math.min(spin.x_min, m.x); spin.x_max = Math.max(spin.x_max, m.x);
            spin.y_min = Math.min(spin.y_min, m.y); spin.y_max = Math.max(spin.y_max, m.y);
          }
          show();  // also after a save re-rendered the card
        },
      };
    }

    function render() {
      ctx.box.textContent = '';
      for (const k of Object.keys(cards)) delete cards[k];
      if (!status) return;
      for (const axis of status.el ? ['az', 'el'] : ['az']) {
        const sensor = status[axis].sensor || v(axis + '.sensor');
        const card = el('div', { class: 'cal', id: 'cal-' + axis },
          el('h2', {}, `${NAMES[axis]} sensor (${sensor})`));
        const make = sensor === 'pot' ? potCard : sensor === 'ma3' ? ma3Card : sensor === 'mag' ? magCard : null;
        if (make) {
          cards[axis] = make(axis, card);
          cards[axis].update(status);
        }
        ctx.box.append(card);
      }
    }

    /** Re-renders when the settings or the rotator's shape changed. */
    function refresh(force) {
      if (!status) return;
      const shape = ['az', 'el'].map((a) => (status[a] ? status[a].sensor : '-')).join('/');
      if (force || ctx.values() !== shownValues || shape !== shownShape) {
        shownValues = ctx.values();
        shownShape = shape;
        render();
      }
    }

    return {
      /** Every live status: updates the readings, re-renders after a reload. */
      update(st) {
        status = st;
        refresh(false);
        for (const [axis, card] of Object.entries(cards)) if (st[axis]) card.update(st);
      },
    };
  }

  return { create };
})();
