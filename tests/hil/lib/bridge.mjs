// A serial port for real clients: socat makes a pty and connects it to a
// unix socket served here, whose bytes go to a CDC endpoint of the emulated
// chip (lib/board.mjs ports) and back. `rotctl -m 603 -r <pty>` then talks
// to the firmware exactly as to /dev/ttyACM1. The endpoint is anything with
// write(bytes) and an onData(bytes) callback (a fake one in the unit test).
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { createServer } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export class PtyBridge {
  /** opts: { endpoint, ptyPath (default: in a temporary directory), socat (binary) } */
  constructor(opts) {
    this.endpoint = opts.endpoint;
    this.dir = mkdtempSync(join(tmpdir(), 'rotord-hil-'));
    this.ptyPath = opts.ptyPath ?? join(this.dir, 'ttyACM');
    this.socketPath = join(this.dir, 'cdc.sock');
    this.socat = opts.socat ?? 'socat';
    this.socket = null;
    this.bytesToDevice = 0;
    this.bytesToHost = 0;
  }

  async start() {
    this.server = createServer((socket) => {
      this.socket = socket;
      socket.on('data', (data) => {
        this.bytesToDevice += data.length;
        this.endpoint.write(data);
      });
      socket.on('close', () => {
        if (this.socket === socket) this.socket = null;
      });
      socket.on('error', () => {});
    });
    await new Promise((resolve) => this.server.listen(this.socketPath, resolve));
    // The device's replies go to whoever holds the pty; with nobody there
    // (socat not yet connected) they are dropped, as USB drops them.
    this.endpoint.onData = (bytes) => {
      if (!this.socket) return;
      this.bytesToHost += bytes.length;
      this.socket.write(Buffer.from(bytes));
    };
    this.proc = spawn(this.socat, [`PTY,link=${this.ptyPath},raw,echo=0`, `UNIX-CONNECT:${this.socketPath}`], {
      stdio: ['ignore', 'ignore', 'inherit'],
    });
    // socat is a real process: poll until it has connected (bounded, liveness only).
    for (let i = 0; i < 200 && !(this.socket && existsSync(this.ptyPath)); i++)
      await new Promise((r) => setTimeout(r, 10));
    if (!this.socket || !existsSync(this.ptyPath)) throw new Error('socat did not connect the pty');
    return this.ptyPath;
  }

  async stop() {
    if (this.proc && this.proc.exitCode === null) {
      const exited = new Promise((r) => this.proc.once('exit', r));
      this.proc.kill();
      await exited;
    }
    this.socket?.destroy();
    await new Promise((r) => this.server?.close(r) ?? r());
    rmSync(this.dir, { recursive: true, force: true });
  }
}
