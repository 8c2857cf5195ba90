#!/bin/bash
# Under systemd rotord's lines carry their syslog priority ("<6>ready",
# "<3>..."), which journald turns into the entry's priority; elsewhere they
# do not. The real binary, its output going to a file that JOURNAL_STREAM
# names the way systemd names the journal's stream (device:inode of fd 1/2).
set -u
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
pid=
trap '[ -n "$pid" ] && kill "$pid" 2>/dev/null; rm -rf "$dir"' EXIT
no_ports=(--web-port 0 --wrc-port 0 --rotctld-port 0 --gs232-port 0 --easycomm-port 0)
export XDG_CONFIG_HOME="$dir"

# An error: exit 2 with a <3> line, no "rotord: " (the journal shows rotord[pid]).
: >"$dir/err"
JOURNAL_STREAM=$(stat -c '%d:%i' "$dir/err") "$ROTORD" "${no_ports[@]}" --bind nonsense \
  >>"$dir/err" 2>&1
rc=$?
cat "$dir/err"
[ "$rc" -eq 2 ] || fail "exit code $rc, not 2"
grep -qx '<3>invalid bind address .nonsense.' "$dir/err" || fail "no <3> error line"

# Info lines and the stop: <6>, and nothing without a prefix.
: >"$dir/out"
JOURNAL_STREAM=$(stat -c '%d:%i' "$dir/out") "$ROTORD" "${no_ports[@]}" --log-level debug \
  >>"$dir/out" 2>&1 &
pid=$!
# rotord works at its own pace: wait (at most 20 s) for it to say ready.
for _ in $(seq 200); do grep -qx '<6>ready' "$dir/out" && break; sleep 0.1; done
kill -TERM "$pid"
wait "$pid"
rc=$?
pid=
cat "$dir/out"
[ "$rc" -eq 0 ] || fail "exit code $rc after SIGTERM"
grep -qx '<6>ready' "$dir/out" || fail "no <6>ready line"
grep -qx '<6>SIGTERM (15), stopping the motors' "$dir/out" || fail "no <6> stop line"
grep -v '^<[3467]>' "$dir/out" && fail "a line without a priority prefix"

# The same variable naming another stream (inherited, output redirected):
# plain lines as before.
JOURNAL_STREAM=$(stat -c '%d:%i' "$dir/err") "$ROTORD" "${no_ports[@]}" --bind nonsense \
  >"$dir/plain" 2>&1
grep -qx 'rotord: invalid bind address .nonsense.' "$dir/plain" || fail "prefix on a plain stream"
echo PASS
