// Access control on the control and settings pages: log out, the control
// lock (take, release, who holds it) and, on the settings page, the web
// password and the REST tokens. GET /api/auth says what applies.
'use strict';

const rotordAccess = (() => {
  const $ = (id) => document.getElementById(id);
  let auth = null;

  function el(tag, attrs, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === 'class') e.className = v; else if (v !== undefined && v !== null) e.setAttribute(k, v);
    }
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  async function refresh() {
    const r = await rotord.get('/api/auth');
    if (r.status !== 200) return;
    auth = r.body;
    const logout = $('logout');
    if (logout) logout.hidden = !(auth.enabled && auth.logged_in);
    showLock(auth.lock);
  }

  function showLock(lock) {
    const box = $('lock');
    if (!box || !lock) return;
    const info = $('lock-info');
    const button = $('lock-button');
    const mine = auth && auth.lock && auth.lock.held && auth.lock.mine && lock.held;
    const min = Math.ceil((lock.remaining_s || 0) / 60);
    if (!lock.held) {
      info.textContent = '';
      info.className = 'lockinfo';
      button.textContent = 'Take control (10 min)';
      button.dataset.action = 'lock';
      button.hidden = auth && !auth.may_control;
    } else if (mine) {
      info.textContent = `you have control (${min} min left)`;
      info.className = 'lockinfo';
      button.textContent = 'Release control';
      button.dataset.action = 'unlock';
      button.hidden = false;
    } else {
      info.textContent = `locked by ${lock.by} (${min} min left): read-only, STOP works`;
      info.className = 'lockinfo other';
      button.hidden = true;
    }
  }

  function wire(msg) {
    const logout = $('logout');
    if (logout) {
      logout.addEventListener('click', async () => {
        await rotord.post('/api/logout', {});
        location.replace('/login.html');
      });
    }
    const button = $('lock-button');
    if (button) {
      button.addEventListener('click', async () => {
        const action = button.dataset.action;
        const r = await rotord.post('/api/' + action, action === 'lock' ? { minutes: 10 } : {});
        if (r.status !== 200) rotord.message(msg, (r.body && r.body.error) || `error ${r.status}`, false);
        await refresh();
      });
    }
    refresh();
  }

  /** From each live status: the lock's state (whose it is comes from /api/auth). */
  function update(status) {
    if (!status || !status.lock) return;
    const was = auth && auth.lock;
    if (!was || was.held !== status.lock.held) return refresh();
    auth.lock.remaining_s = status.lock.remaining_s;
    showLock(status.lock);
  }

  // --- settings page: password and tokens ------------------------------------
  async function card(box) {
    const r = await rotord.get('/api/auth');
    if (r.status !== 200) return;
    auth = r.body;
    box.textContent = '';
    // Its own message line: the form's is at the end of a long page.
    const msg = el('p', { id: 'access-msg', class: 'msg', role: 'status' });
    const legend = el('legend', {}, 'Access control');
    const state = el('p', { id: 'access-state' }, auth.enabled
      ? 'On: every page and REST call needs the login or a token (STOP never does).'
      : 'Off: anyone who can reach the controller may use it. Set a password to turn it on.');
    const password = el('input', { id: 'new-password', type: 'password', autocomplete: 'new-password',
      minlength: 8, maxlength: 63, placeholder: '8-63 characters' });
    const set = el('button', { id: 'set-password', type: 'button' }, auth.enabled ? 'Change password' : 'Set password');
    const off = el('button', { id: 'remove-password', type: 'button' }, 'Turn off');
    off.hidden = !auth.enabled;
    set.addEventListener('click', async () => {
      rotord.message(msg, 'hashing the password…', true);
      const s = await rotord.post('/api/password', { password: password.value });
      rotord.message(msg, s.status === 200 ? 'password set: access control is on' : (s.body && s.body.error) || `error ${s.status}`, s.status === 200);
      if (s.status === 200) card(box);
    });
    off.addEventListener('click', async () => {
      if (!confirm('Turn access control off? Anyone who can reach the controller may then use it.')) return;
      const s = await rotord.post('/api/password', { password: '' });
      rotord.message(msg, s.status === 200 ? 'access control is off' : (s.body && s.body.error) || `error ${s.status}`, s.status === 200);
      if (s.status === 200) card(box);
    });
    const list = el('ul', { id: 'tokens' });
    const shown = el('p', { id: 'new-token', class: 'token' });
    const name = el('input', { id: 'token-name', maxlength: 16, placeholder: 'name, e.g. gpredict' });
    const scope = el('select', { id: 'token-scope' }, el('option', { value: 'read' }, 'read-only'),
      el('option', { value: 'control' }, 'control'));
    const add = el('button', { id: 'token-create', type: 'button' }, 'Make token');
    add.addEventListener('click', async () => {
      const s = await rotord.post('/api/tokens', { name: name.value, scope: scope.value });
      if (s.status === 201) {
        shown.textContent = `${s.body.name}: ${s.body.token}  (shown only now: copy it)`;
        await tokens(list, msg);
      } else {
        rotord.message(msg, (s.body && s.body.error) || `error ${s.status}`, false);
      }
    });
    box.append(legend, state, el('div', { class: 'access' }, password, set, off),
      el('h3', {}, 'REST tokens'), list, el('div', { class: 'access' }, name, scope, add), shown, msg);
    await tokens(list, msg);
  }

  async function tokens(list, msg) {
    const r = await rotord.get('/api/tokens');
    list.textContent = '';
    if (r.status !== 200) return;
    for (const t of r.body.tokens) {
      const revoke = el('button', { type: 'button' }, 'Revoke');
      revoke.addEventListener('click', async () => {
        const s = await rotord.post('/api/tokens/revoke', { name: t.name });
        if (s.status !== 200) rotord.message(msg, (s.body && s.body.error) || `error ${s.status}`, false);
        await tokens(list, msg);
      });
      list.append(el('li', {}, `${t.name} (${t.scope}) `, revoke));
    }
  }

  return { wire, update, card };
})();
