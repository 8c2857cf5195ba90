// Shared by the control and settings pages: REST calls and the live event
// stream with reconnection. Plain JS, no framework: the files are compiled
// into the firmware and must stay small.
'use strict';

const rotord = (() => {
  /**
   * One REST call (a body of `type` when given); resolves to {status, body},
   * never throws.
   */
  async function request(method, path, body, type) {
    try {
      const r = await fetch(path, { method, headers: type ? { 'Content-Type': type } : {}, body });
      let parsed = null;
      try { parsed = await r.json(); } catch (e) { parsed = null; }
      // Access control is on and the login ran out (or never was).
      if (r.status === 401) location.replace('/login.html');
      return { status: r.status, body: parsed };
    } catch (e) {
      return { status: 0, body: { error: 'no connection to the controller' } };
    }
  }
  /** GET (no body) or POST JSON. */
  const api = (path, body) => (body === undefined ? request('GET', path)
    : request('POST', path, JSON.stringify(body), 'application/json'));
  const post = (path, body) => api(path, body === undefined ? {} : body);
  const get = (path) => api(path);

  /**
   * Subscribes to /api/events. EventSource reconnects by itself after a
   * dropped stream; when it gives up (an HTTP error such as 503), start over.
   */
  function live(onStatus) {
    const conn = document.getElementById('conn');
    let source = null;
    let watchdog = 0;
    const setConn = (text, cls) => { if (conn) { conn.textContent = text; conn.className = 'conn ' + cls; } };
    function arm() {
      clearTimeout(watchdog);
      // The server sends at least one event a second; silence means a stalled link.
      watchdog = setTimeout(() => { setConn('reconnecting…', 'lost'); open(); }, 5000);
    }
    function open() {
      if (source) source.close();
      source = new EventSource('/api/events');
      source.onopen = () => { setConn('live', 'live'); arm(); };
      source.onmessage = (e) => {
        arm();
        try { onStatus(JSON.parse(e.data)); } catch (err) { /* ignore a torn event */ }
      };
      source.onerror = () => {
        setConn('reconnecting…', 'lost');
        if (source.readyState === EventSource.CLOSED) {
          api('/api/auth');  // a 401 there goes to the login page
          setTimeout(open, 2000);
        }
      };
    }
    open();
    window.addEventListener('pagehide', () => { if (source) source.close(); });
  }

  function message(el, text, ok) {
    el.textContent = text || '';
    el.className = 'msg ' + (text ? (ok ? 'ok' : 'error') : '');
  }

  // Rounds -0.04 to "0.0", not "-0.0".
  const fmt = (v, digits = 1) =>
    (typeof v === 'number' && isFinite(v) ? (Math.abs(v) < 0.5 * 10 ** -digits ? 0 : v).toFixed(digits) : '–');

  /**
   * A Maidenhead locator (2 to 8 characters, JO62QM) as [lat, lon] of its
   * square's centre, or null when the text is not one. Wherever a position
   * is asked for, a locator typed there is understood.
   */
  function locator(text) {
    const s = String(text).trim().toUpperCase();
    if (!/^[A-R]{2}([0-9]{2}([A-X]{2}([0-9]{2})?)?)?$/.test(s)) return null;
    let lon = (s.charCodeAt(0) - 65) * 20 - 180;
    let lat = (s.charCodeAt(1) - 65) * 10 - 90;
    let w = 20;
    let h = 10;
    if (s.length >= 4) { w = 2; h = 1; lon += Number(s[2]) * 2; lat += Number(s[3]); }
    if (s.length >= 6) { w /= 24; h /= 24; lon += (s.charCodeAt(4) - 65) * w; lat += (s.charCodeAt(5) - 65) * h; }
    if (s.length >= 8) { w /= 10; h /= 10; lon += Number(s[6]) * w; lat += Number(s[7]) * h; }
    return [lat + h / 2, lon + w / 2];
  }

  return { api, request, post, get, live, message, fmt, locator };
})();
