#!/usr/bin/env bash
# rotord's rotctld port against the real thing: the same command script is
# sent to Hamlib's `rotctld -m 1` (dummy rotator, 4.5.4) and to rotord, and
# every reply that the reference produces deterministically is compared byte
# for byte. Both are given the same limits (rotord's simulated SPID, az
# -180..540 and el 0..180; rotctld via -C), so even \dump_state must match.
# Then Hamlib's own client, rotctl -m 2, runs the same commands against both.
# Position, info, status, caps and known deviations (docs/protocols/rotctld.md)
# are sent to keep both sessions in step but not compared.
set -euo pipefail
: "${ROTORD:?set ROTORD to the rotord binary}"
command -v rotctld >/dev/null || { echo "rotctld (libhamlib-utils) not installed"; exit 1; }

work=$(mktemp -d /tmp/rotord-rotctld-cmp-XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
ref_port=$(free_port)
our_port=$(free_port)

rotctld -m 1 -T 127.0.0.1 -t "$ref_port" -C max_az=540,max_el=180 >"$work/rotctld.log" 2>&1 &
pids+=($!)
XDG_CONFIG_HOME="$work/config" "$ROTORD" --bind 127.0.0.1 --sim spid --speedup 20 \
  --rotctld-port "$our_port" --web-port 0 --wrc-port 0 --gs232-port 0 --easycomm-port 0 \
  >"$work/rotord.log" 2>&1 &
pids+=($!)

# Both daemons start at their own pace: poll (at most 10 s, liveness only)
# until rotord says ready and the reference rotctld accepts a connection.
for _ in $(seq 100); do
  if grep -q "rotord: ready" "$work/rotord.log" &&
    python3 -c "import socket,sys; socket.create_connection(('127.0.0.1', $ref_port)).close()" 2>/dev/null; then
    break
  fi
  sleep 0.1
done
grep -q "rotord: ready" "$work/rotord.log" || { cat "$work/rotord.log"; exit 1; }

python3 - "$ref_port" "$our_port" <<'EOF'
import select, socket, sys, time

ref_port, our_port = int(sys.argv[1]), int(sys.argv[2])
SEPARATORS = "!\"$%&'()*,-./:;<=>?@[]^`{|}~"

# (bytes, compared). A step that is not compared still runs on both servers.
STEPS = [
    (b"\\dump_state\n", True),
    (b"P 10 20\n", True), (b"P 500 170\n", True), (b"P -180 0\n", True),
    (b"P 540 180\n", True), (b"P 541 20\n", True), (b"P -181 20\n", True),
    (b"P 10 181\n", True), (b"P 10 -1\n", True), (b"P abc 20\n", True),
    (b"P 10 x\n", True), (b"P ?\n", True), (b"P 10,5 20,5\n", True),
    (b"P 11.5 21.5\r\n", True), (b"P 12 22\r", True), (b"P +13 +23\n", True),
    (b"P 14abc 24\n", True), (b"\\set_pos 20 30\n", True),
    (b"p\n", False), (b"\\get_pos\n", False), (b"_\n", False), (b"s\n", False),
    (b"S\n", True), (b"K\n", True), (b"\\park\n", True), (b"\\stop\n", True),
    (b"R 1\n", True), (b"R abc\n", True), (b"\\reset 1\n", True),
    (b"M 8 50\n", True), (b"S\n", True), (b"M 16 10\n", True), (b"S\n", True),
    (b"M UP 50\n", True), (b"S\n", True), (b"M DOWN 1\n", True), (b"S\n", True),
    (b"M CCW -1\n", True), (b"S\n", True), (b"M RIGHT 100\n", True), (b"S\n", True),
    (b"M LEFT 5\n", True), (b"S\n", True), (b"M CW 5\n", True), (b"S\n", True),
    (b"\\move 2 50\n", True), (b"S\n", True),
    (b"M 3 50\n", True), (b"M 8 x\n", True), (b"M abc 5\n", True),
    (b"V SPEED 2\n", True), (b"v SPEED\n", True), (b"\\set_level SPEED 3\n", True),
    (b"\\get_level SPEED\n", True), (b"V FOO 1\n", True), (b"v FOO\n", True),
    (b"U ?\n", True), (b"u ?\n", True), (b"X ?\n", True), (b"x ?\n", True),
    (b"U FOO 1\n", True), (b"u FOO\n", True), (b"X FOO 1\n", True), (b"x FOO\n", True),
    (b"C foo 1\n", True), (b"C min_az -90\n", True), (b"\\dump_state\n", True),
    (b"\\set_conf min_az -180\n", True), (b"\\dump_state\n", True),
    (b"w XYZ\n", True), (b"\\send_cmd XYZ\n", True), (b"\\pause 0\n", True),
    (b"\x8c 0\n", True), (b"\x8f\n", True),
    # framing: split packets, arguments on later lines, CR/LF variants
    (b"P 1", True), (b"0 20\n", True), (b"P\n15\n25\n", True), (b"P 10\n", True),
    (b"20\n", True), (b"R\n1\n", True), (b"M\n8\n", True), (b"50\n", True), (b"S\n", True),
    (b"S\r\nS\r\n", True), (b"S K S\n", True), (b" S\n", True), (b"#comment\nS\n", True),
    (b"\n\r\n", True), (b"S\rS\r", True),
    # Extended Response Protocol
    (b"+P 10 20\n", True), (b";P 10 20\n", True), (b"|P 1 2\n", True),
    (b"+P 10 195\n", True), (b"+S\n", True), (b"+K\n", True), (b"+R 1\n", True),
    (b"+M 8 50\n", True), (b"S\n", True), (b"+\\move RIGHT 10\n", True), (b"S\n", True),
    (b"+\\dump_state\n", True), (b";\\dump_state\n", True), (b"|\\dump_state\n", True),
    (b"+V SPEED 2\n", True), (b"+v SPEED\n", True), (b"+\\set_conf min_az -180\n", True),
    (b"+C foo 1\n", True), (b"+w XYZ\n", True), (b"++S\n", True), (b"+;S\n", True),
    (b"+p\n", False), (b";p\n", False), (b"+_\n", False), (b"+s\n", False),
    # locator helpers, edge cases included
] + [(c.encode() + b"\n", True) for c in [
    "L 2.0 51.0 6", "l JO01aa", "B 0 51 2 52", "A 10", "a 100", "D 51 30 0 0", "d 51.5",
    "E 51 30.5 0", "e 51.5", "+L 2 51 6", ";l JO01aa", "+B 0 51 2 52", "+d -96.8333",
    "d 270", "d -270", "d 180", "d -180", "e -0.5", "A 0", "A 180", "A 270", "A 400", "A -5",
    "B 0 91 0 0", "B 0 0 0 0", "B 0 0 180 0", "B -74.0060 40.7128 139.6917 35.6895",
    "L 2 51 12", "L 2 51 14", "L 2 51 1", "L -180 -90 6", "L 179.99 89.99 6", "l JO",
    "l jo01AA55bb", "l ZZ", "l J", "l JO01AA55bb77xx", "D -51 -30 -15.5 1", "E 51 30,5 0",
    "L 2,5 51 6", "\\qrb 0 51 2 52", "\\a_sp2a_lp 90", "\\d_sp2d_lp 1000"]
] + [((sep + "S\n").encode(), True) for sep in SEPARATORS] + [
    (b"1\n", False), (b"v ?\n", False),
]

def connect(port):
    s = socket.create_connection(("127.0.0.1", port))
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return s

def collect(socks, quiet=0.15, limit=3.0):
    """Everything each socket receives until all are quiet for `quiet` s."""
    got = {s: b"" for s in socks}
    closed = set()
    deadline = time.time() + limit
    while time.time() < deadline:
        ready, _, _ = select.select([s for s in socks if s not in closed], [], [], quiet)
        if not ready:
            break
        for s in ready:
            data = s.recv(65536)
            if data:
                got[s] += data
            else:
                got[s] += b"<EOF>"
                closed.add(s)
        if len(closed) == len(socks):
            break
    return got

ref, ours = connect(ref_port), connect(our_port)
failures = compared = 0
for data, compare in STEPS:
    ref.sendall(data)
    ours.sendall(data)
    got = collect([ref, ours])
    # A server delayed by a loaded machine (CI runs tests in parallel) answers
    # after the quiet time: when the two differ, wait longer for the late
    # bytes before calling it a difference. Both transcripts stay in step,
    # because whatever arrives late is still added to this step.
    for _ in range(4):
        if not compare or got[ref] == got[ours]:
            break
        more = collect([ref, ours], quiet=0.5)
        if not more[ref] and not more[ours]:
            break
        got = {s: got[s] + more[s] for s in got}
    if not compare:
        # Every uncompared step has a reply on both sides: wait for a late
        # one, so it cannot spill into the next, compared step.
        for sock in (ref, ours):
            if not got[sock]:
                got[sock] = collect([sock], quiet=1.0)[sock]
        if not got[ours]:
            print(f"NO REPLY from rotord to {data!r}")
            failures += 1
        continue
    compared += 1
    if got[ref] != got[ours]:
        failures += 1
        print(f"DIFF for {data!r}:\n  rotctld: {got[ref]!r}\n  rotord:  {got[ours]!r}")
# q closes both without a reply
ref.sendall(b"q\n")
ours.sendall(b"q\n")
got = collect([ref, ours], quiet=1.0)
if got[ref] != b"<EOF>" or got[ours] != b"<EOF>":
    failures += 1
    print(f"q: rotctld {got[ref]!r} rotord {got[ours]!r}")
print(f"rotctld comparison: {compared} steps compared byte for byte, {failures} differences")
sys.exit(1 if failures else 0)
EOF

# Hamlib's NET rotctl client against both servers: same results, same output.
status=0
for cmds in "P 10 20 S K M 2 50 S R 1" "P 600 20" "P 10 200" "P -180 0 P 540 180 S" \
  "M RIGHT 100 S M UP 1 S M 16 -1 S" "V SPEED 2" "w XYZ"; do
  ref_out=$(timeout 20 rotctl -m 2 -r "127.0.0.1:$ref_port" $cmds 2>&1; echo "rc=$?")
  our_out=$(timeout 20 rotctl -m 2 -r "127.0.0.1:$our_port" $cmds 2>&1; echo "rc=$?")
  if [ "$ref_out" != "$our_out" ]; then
    echo "rotctl -m 2 $cmds differs:"
    diff <(echo "$ref_out") <(echo "$our_out") || true
    status=1
  else
    echo "rotctl -m 2 $cmds: same (${ref_out##*rc=})"
  fi
done
exit $status
