// The login page: the only page served before logging in (with style.css),
// so it shares no script with the others. STOP works without a login.
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const msg = $('msg');
  const say = (text, ok) => { msg.textContent = text; msg.className = 'msg ' + (ok ? 'ok' : 'error'); };

  async function post(path, body) {
    try {
      const r = await fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify(body) });
      let parsed = null;
      try { parsed = await r.json(); } catch (e) { parsed = null; }
      return { status: r.status, body: parsed };
    } catch (e) {
      return { status: 0, body: { error: 'no connection to the controller' } };
    }
  }

  $('login').addEventListener('submit', async (e) => {
    e.preventDefault();
    $('submit').disabled = true;
    say('checking…', true);
    const r = await post('/api/login', { password: $('password').value });
    $('submit').disabled = false;
    if (r.status === 200) {
      say('logged in', true);
      location.replace('/');
      return;
    }
    $('password').select();
    say((r.body && r.body.error) || `error ${r.status}`, false);
  });

  $('stop').addEventListener('click', async () => {
    const r = await post('/api/stop', {});
    say(r.status === 200 ? 'stopped' : (r.body && r.body.error) || 'failed', r.status === 200);
  });
})();
