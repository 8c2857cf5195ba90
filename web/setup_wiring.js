// The set-up page's wiring step (docs/commissioning.md, "The wiring"): the
// Wiring rows of the settings table that apply to this platform and to the
// drive, sensor and axes chosen (their conditions, settings_filter.js), and
// the boards the docs describe as presets. A preset fills the fields with the
// documented wiring (the table's defaults: docs/hardware.md for the Pico W,
// docs/gpiod.md for the Raspberry Pi) and the board's own polarity or PWM
// chip; nothing is saved until "Save the wiring".
'use strict';

const rotordWiring = (() => {
  // drive: 'relay' stands for every relay drive (one or two speeds, voltage
  // select), 'hbridge' for the H-bridge.
  const BOARDS = [
    { id: 'pico-relay', platform: 'pico_w', drive: 'relay',
      name: 'Relay board, a high input switches a relay on (docs/hardware.md)', set: {} },
    { id: 'pico-hbridge', platform: 'pico_w', drive: 'hbridge',
      name: 'H-bridge board, PWM at 20 kHz on GPIO 14/15 (docs/hardware.md)', set: {} },
    { id: 'pi-relay-high', platform: 'gpiod', drive: 'relay',
      name: 'Relay board energised by a high input (docs/gpiod.md)',
      set: { 'gpiod.outputs_active_low': false } },
    { id: 'pi-relay-low', platform: 'gpiod', drive: 'relay',
      name: 'Opto-isolated relay board energised by a low input, as most are (docs/gpiod.md)',
      set: { 'gpiod.outputs_active_low': true } },
    { id: 'pi-hbridge', platform: 'gpiod', drive: 'hbridge',
      name: 'H-bridge board on the hardware PWM, dtoverlay=pwm-2chan: GPIO 18/19 (docs/gpiod.md)',
      set: { 'pwm.chip': 0 } },
  ];
  const PLATFORMS = { pico_w: 'Pico W', gpiod: 'Raspberry Pi' };

  /**
   * Wires the step: `box` gets the fields, `boards` the presets, `forSelect`
   * the platform choice (shown only in the simulator, which has no wiring
   * of its own: the owner prepares a board's settings there).
   */
  function create({ schema, values, box, boards, forSelect, forRow, note }) {
    const platform = () => (schema.platform === 'sim' || !schema.platform ? forSelect.value : schema.platform);
    const inputs = {};

    function driveKind() {
      return values()['az.drive'] === 'hbridge' ? 'hbridge' : 'relay';
    }

    function rows() {
      const valueOf = (key) => values()[key];
      return schema.settings.filter((d) => d.group === 'Wiring' && !d.advanced &&
        rotordSettingsFilter.holds(d.when, platform(), valueOf));
    }

    function field(d, value) {
      const label = document.createElement('label');
      label.className = 'pin';
      const name = document.createElement('span');
      name.textContent = d.label;
      const key = document.createElement('code');
      key.className = 'key';
      key.textContent = d.key;
      const input = document.createElement(d.type === 'enum' ? 'select' : 'input');
      if (d.type === 'bool') {
        input.type = 'checkbox';
        input.checked = !!value;
      } else if (d.type === 'enum') {
        for (const c of d.choices) input.append(new Option(c, c));
        input.value = value;
      } else {
        Object.assign(input, { type: 'text', inputMode: 'numeric', value: String(value), autocomplete: 'off' });
      }
      input.id = 'pin-' + d.key;
      input.dataset.key = d.key;
      inputs[d.key] = { input, def: d };
      label.append(name, ' ', key, ' ', input);
      return label;
    }

    /** Shows the fields that apply, with the given values (a preset's) or the saved ones. */
    function show(preset) {
      box.textContent = '';
      for (const k of Object.keys(inputs)) delete inputs[k];
      const list = rows();
      for (const d of list) {
        const v = preset && d.key in preset ? preset[d.key] : values()[d.key];
        box.append(field(d, v));
      }
      note.textContent = list.length ? '' : 'Nothing to wire here.';
      boards.textContent = '';
      for (const b of BOARDS.filter((x) => x.platform === platform() && x.drive === driveKind())) {
        const button = document.createElement('button');
        button.type = 'button';
        button.id = 'board-' + b.id;
        button.textContent = b.name;
        button.addEventListener('click', () => show(presetValues(b)));
        boards.append(button);
      }
    }

    /** A board: the documented wiring (each applicable row's default), then its own settings. */
    function presetValues(board) {
      const v = {};
      for (const d of rows()) v[d.key] = d.default;
      return Object.assign(v, board.set);
    }

    /** The changed fields, or an error naming the field that is not a pin number. */
    function changes() {
      const doc = {};
      for (const [key, { input, def }] of Object.entries(inputs)) {
        let v;
        if (def.type === 'bool') v = input.checked;
        else if (def.type === 'enum') v = input.value;
        else {
          v = Number(input.value.trim());
          if (input.value.trim() === '' || !Number.isInteger(v)) {
            return { error: `${key}: a whole number, -1 = not wired` };
          }
        }
        if (v !== values()[key]) doc[key] = v;
      }
      return { doc };
    }

    const simulated = schema.platform === 'sim' || !schema.platform;
    forRow.hidden = !simulated;
    if (simulated) {
      for (const [value, name] of Object.entries(PLATFORMS)) forSelect.append(new Option(name, value));
      forSelect.addEventListener('change', () => show());
    }
    return { show, changes };
  }

  return { create };
})();
