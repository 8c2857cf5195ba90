// The pty bridge without the emulator: socat's pty <-> the harness's socket
// <-> a fake CDC endpoint that answers like the firmware's GS-232 port, with
// Hamlib's rotctl as the client.
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { closeSync, constants, openSync, readSync, writeSync } from 'node:fs';
import { test } from 'node:test';
import { promisify } from 'node:util';
import { PtyBridge } from '../lib/bridge.mjs';

const run = promisify(execFile);

/** A CDC endpoint: GS-232B's C2 and M, and an echo of anything else. */
function fakeGs232() {
  const ep = { onData: null, received: '', azDeg: 123 };
  ep.write = (bytes) => {
    ep.received += Buffer.from(bytes).toString('latin1');
    let cr;
    while ((cr = ep.received.indexOf('\r')) >= 0) {
      const line = ep.received.slice(0, cr);
      ep.received = ep.received.slice(cr + 1);
      let reply;
      if (line === 'C2') reply = `AZ=${String(ep.azDeg).padStart(3, '0')}  EL=000\r\n`;
      else if (/^W\d{3} \d{3}$/.test(line)) {
        ep.azDeg = Number(line.slice(1, 4));
        reply = '\r\n';
      } else reply = `echo:${line}\r\n`;
      setImmediate(() => ep.onData?.(new TextEncoder().encode(reply)));
    }
  };
  return ep;
}

test('rotctl -m 603 reads and sets the position through the pty', async () => {
  const ep = fakeGs232();
  const bridge = new PtyBridge({ endpoint: ep });
  const pty = await bridge.start();
  try {
    const p = await run('rotctl', ['-m', '603', '-r', pty, 'p'], { timeout: 20000 });
    assert.deepEqual(p.stdout.trim().split('\n').map(Number), [123, 0]);
    await run('rotctl', ['-m', '603', '-r', pty, 'P', '45', '0'], { timeout: 20000 });
    assert.equal(ep.azDeg, 45);
    // A second program opening the same pty later is served too (socat stays).
    const again = await run('rotctl', ['-m', '603', '-r', pty, 'p'], { timeout: 20000 });
    assert.equal(Number(again.stdout.trim().split('\n')[0]), 45);
  } finally {
    await bridge.stop();
  }
});

test('bytes cross the bridge unchanged both ways (raw pty, no echo, no CR/LF mapping)', async () => {
  const ep = fakeGs232();
  const bridge = new PtyBridge({ endpoint: ep });
  const pty = await bridge.start();
  // Non-blocking: the fake endpoint answers from this same event loop.
  const fd = openSync(pty, constants.O_RDWR | constants.O_NOCTTY | constants.O_NONBLOCK);
  try {
    writeSync(fd, 'hello\r');
    let got = '';
    const buf = Buffer.alloc(256);
    // Polls for the echo through socat (a real process), bounded at 10 s: liveness only.
    const deadline = Date.now() + 10000;
    while (!got.endsWith('\r\n') && Date.now() < deadline) {
      await new Promise((r) => setTimeout(r, 10));
      try {
        const n = readSync(fd, buf, 0, buf.length, null);
        got += buf.subarray(0, n).toString('latin1');
      } catch (e) {
        if (e.code !== 'EAGAIN') throw e;
      }
    }
    assert.equal(got, 'echo:hello\r\n');
    assert.equal(bridge.bytesToDevice, 6);
    assert.equal(bridge.bytesToHost, 12);
  } finally {
    closeSync(fd);
    await bridge.stop();
  }
});
