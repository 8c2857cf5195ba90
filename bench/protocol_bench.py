"""Protocol latency and throughput (real loopback sockets, wall clock).

rotord's rotctld port and Hamlib's own `rotctld -m 1` (dummy rotator) run in
the same session under the same compiled load client (rotord_load_client):
`p` round trip (median, p99) and requests per second with 1, 8 and 100
closed-loop clients, each server in turn, reported side by side and as
rotord / Hamlib ratios. rotord gets net.max_clients 128 for the 100-client
run. Also the peak RSS of rotord with every protocol port full.
"""
import json
import os
import shutil
import socket
import subprocess
import tempfile
import time

CLIENT_COUNTS = (1, 8, 100)
SECONDS = 1.0
REPEATS = 3  # interleaved; the best run of each server counts (the machine is shared)


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def wait_port(port, proc, timeout_s=10.0):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"server exited with {proc.returncode}")
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            return
        except OSError:
            time.sleep(0.05)
    raise RuntimeError(f"port {port} not open")


def start_rotord(build_dir, work, settings, ports):
    cfg = os.path.join(work, "settings.json")
    with open(cfg, "w") as f:
        json.dump(settings, f)
    args = [os.path.join(build_dir, "rotord"), "--config", cfg,
            "--bind", "127.0.0.1", "--sim", "g5500"]
    for name in ("web", "rotctld", "wrc", "gs232", "easycomm", "seed"):
        args += [f"--{name}-port", str(ports.get(name, 0))]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return proc


def start_rotord_ready(build_dir, work, settings, names):
    """Starts rotord on fresh free ports; retries when a port was taken
    between picking it and binding (other tests run alongside)."""
    for attempt in range(3):
        ports = {name: free_port() for name in names}
        proc = start_rotord(build_dir, work, settings, ports)
        try:
            for p in ports.values():
                wait_port(p, proc)
            return proc, ports
        except RuntimeError:
            stop(proc)
            if attempt == 2:
                raise
    raise RuntimeError("unreachable")


def load_once(build_dir, port, clients):
    out = subprocess.run([os.path.join(build_dir, "bench", "rotord_load_client"), str(port),
                          str(clients), str(SECONDS)], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def load(build_dir, port, clients):
    runs = [load_once(build_dir, port, clients) for _ in range(REPEATS)]
    return max(runs, key=lambda m: m["requests_per_s"])


def stop(proc):
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def latency_rows(build_dir, work):
    rows = []
    rotctld = shutil.which("rotctld")
    ours, ports = start_rotord_ready(build_dir, work,
                                     {"net.max_clients": 128, "net.max_per_address": 127},
                                     ["rotctld"])
    our_port, ref_port = ports["rotctld"], free_port()
    ref = None
    try:
        if rotctld:
            ref = subprocess.Popen([rotctld, "-m", "1", "-T", "127.0.0.1", "-t", str(ref_port)],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            wait_port(ref_port, ref)
        for n in CLIENT_COUNTS:
            m_ours = load(build_dir, our_port, n)
            metrics = {"rotord_req_per_s": m_ours["requests_per_s"],
                       "rotord_median_us": m_ours["median_us"], "rotord_p99_us": m_ours["p99_us"],
                       "rotord_errors": m_ours["errors"]}
            if ref is not None:
                m_ref = load(build_dir, ref_port, n)
                metrics.update({
                    "hamlib_req_per_s": m_ref["requests_per_s"],
                    "hamlib_median_us": m_ref["median_us"], "hamlib_p99_us": m_ref["p99_us"],
                    "hamlib_errors": m_ref["errors"],
                    "rate_ratio": m_ours["requests_per_s"] / max(m_ref["requests_per_s"], 1e-9),
                    "p99_ratio": m_ours["p99_us"] / max(m_ref["p99_us"], 1e-9),
                    "median_ratio": m_ours["median_us"] / max(m_ref["median_us"], 1e-9)})
            rows.append({"name": f"protocol/rotctld_p/{n}_clients",
                         "inputs": {"clients": n, "seconds": SECONDS}, "metrics": metrics})
    finally:
        stop(ours)
        if ref is not None:
            stop(ref)
    return rows


def peak_rss_row(build_dir, work):
    """rotord (defaults: 8 clients per port) with every protocol port full,
    each client having sent one request, plus the web event streams."""
    proc, ports = start_rotord_ready(build_dir, work, {},
                                     ["web", "rotctld", "wrc", "gs232", "easycomm", "seed"])
    socks = []
    try:
        requests = {"rotctld": b"p\n", "wrc": b"AZ?\r\n", "gs232": b"C2\r", "easycomm": b"AZ EL\n",
                    "seed": b"$pos\n"}
        for name, req in requests.items():
            for _ in range(8):
                s = socket.create_connection(("127.0.0.1", ports[name]))
                s.sendall(req)
                socks.append(s)
        for _ in range(8):
            s = socket.create_connection(("127.0.0.1", ports["web"]))
            s.sendall(b"GET /api/events HTTP/1.1\r\nHost: x\r\n\r\n")
            socks.append(s)
        time.sleep(1.0)  # let every reply and the first pushes go out
        with open(f"/proc/{proc.pid}/status") as f:
            status = dict(line.split(":", 1) for line in f if ":" in line)
        hwm_kib = float(status["VmHWM"].split()[0])
        return [{"name": "footprint/rotord_peak_rss",
                 "inputs": {"clients_per_port": 8, "ports": 5, "event_streams": 8},
                 "metrics": {"peak_rss_kib": hwm_kib, "connections": len(socks)}}]
    finally:
        for s in socks:
            s.close()
        stop(proc)


def run(build_dir):
    with tempfile.TemporaryDirectory(prefix="rotord-bench-") as work:
        rows = []
        for part in (latency_rows, peak_rss_row):
            try:
                rows += part(build_dir, work)
            except (OSError, subprocess.CalledProcessError, RuntimeError) as e:
                print(f"bench: {part.__name__} skipped: {e}")
        return rows
